/* HarmonicForce: an FMI 2.0 co-simulation FMU written without pythonfmu, a test partner of the
 * packed guideway FMU (tests/cosim/test_export_fmu.py). Output F = offset + amplitude
 * sin(2 pi frequency t + phase) [N] at the FMU's current time t [s]; no inputs, no feedthrough.
 * Value references: 0 amplitude [N], 1 frequency [Hz], 2 phase [rad], 3 offset [N], 4 F [N]. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"

#define N_REALS 5
#define VR_F 4

typedef struct {
    fmi2Real r[N_REALS];
    fmi2Real time;
    fmi2CallbackFunctions callbacks;
    fmi2String name;
} Instance;

static void update(Instance *c) {
    c->r[VR_F] = c->r[3] + c->r[0] * sin(2.0 * M_PI * c->r[1] * c->time + c->r[2]);
}

static fmi2Status fail(Instance *c, const char *message) {
    if (c && c->callbacks.logger)
        c->callbacks.logger(c->callbacks.componentEnvironment, c->name, fmi2Error, "logStatusError",
                            message);
    return fmi2Error;
}

const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                              const fmi2CallbackFunctions *callbacks, fmi2Boolean visible,
                              fmi2Boolean logging) {
    (void)resources; (void)visible; (void)logging;
    if (type != fmi2CoSimulation || strcmp(guid, "{5d6b8f0e-harmonic-force-0001}") != 0)
        return NULL;
    Instance *c = calloc(1, sizeof(Instance));
    if (!c) return NULL;
    c->r[0] = 2000.0; c->r[1] = 1000.0;
    c->callbacks = *callbacks;
    c->name = strdup(name);
    update(c);
    return c;
}

void fmi2FreeInstance(fmi2Component c) {
    if (c) { free((void *)((Instance *)c)->name); free(c); }
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cats[]) {
    (void)c; (void)on; (void)n; (void)cats; return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolDefined, fmi2Real tol, fmi2Real start,
                               fmi2Boolean stopDefined, fmi2Real stop) {
    (void)tolDefined; (void)tol; (void)stopDefined; (void)stop;
    ((Instance *)c)->time = start;
    update(c);
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2ExitInitializationMode(fmi2Component c) { update(c); return fmi2OK; }
fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2Reset(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    Instance *inst = c;
    for (size_t i = 0; i < n; i++) {
        if (vr[i] >= N_REALS) return fail(inst, "no Real variable with this value reference");
        v[i] = inst->r[vr[i]];
    }
    return fmi2OK;
}

fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    Instance *inst = c;
    for (size_t i = 0; i < n; i++) {
        if (vr[i] >= VR_F) return fail(inst, "only the parameters (value references 0 to 3) can be set");
        if (!isfinite(v[i])) return fail(inst, "a parameter must be finite");
        inst->r[vr[i]] = v[i];
    }
    update(inst);
    return fmi2OK;
}

fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    (void)vr; (void)v; return n ? fail(c, "no Integer variables") : fmi2OK;
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    (void)vr; (void)v; return n ? fail(c, "no Boolean variables") : fmi2OK;
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    (void)vr; (void)v; return n ? fail(c, "no String variables") : fmi2OK;
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
    (void)vr; (void)v; return n ? fail(c, "no Integer variables") : fmi2OK;
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
    (void)vr; (void)v; return n ? fail(c, "no Boolean variables") : fmi2OK;
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
    (void)vr; (void)v; return n ? fail(c, "no String variables") : fmi2OK;
}

/* canGetAndSetFMUstate, canSerializeFMUstate and providesDirectionalDerivative are false */
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; return fail(c, "no FMU state"); }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)s; return fail(c, "no FMU state"); }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)s; return fail(c, "no FMU state"); }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) {
    (void)s; (void)n; return fail(c, "no FMU state");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) {
    (void)s; (void)b; (void)n; return fail(c, "no FMU state");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) {
    (void)b; (void)n; (void)s; return fail(c, "no FMU state");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real dv[], fmi2Real dz[]) {
    (void)u; (void)nu; (void)z; (void)nz; (void)dv; (void)dz;
    return fail(c, "no directional derivatives");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer order[], const fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v; return fail(c, "no inputs");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer order[], fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v; return fail(c, "no output derivatives");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean noSetPrior) {
    Instance *inst = c;
    (void)noSetPrior;
    if (!(h > 0.0)) return fail(inst, "the communication step must be > 0");
    inst->time = t + h;
    update(inst);
    return fmi2OK;
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2OK; }
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind k, fmi2Status *v) {
    (void)k; (void)v; return fail(c, "no asynchronous steps");
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind k, fmi2Real *v) {
    (void)k; (void)v; return fail(c, "no asynchronous steps");
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind k, fmi2Integer *v) {
    (void)k; (void)v; return fail(c, "no asynchronous steps");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind k, fmi2Boolean *v) {
    (void)k; (void)v; return fail(c, "no asynchronous steps");
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind k, fmi2String *v) {
    (void)k; (void)v; return fail(c, "no asynchronous steps");
}
