/* The FMI 2.0 co-simulation interface of every native guideway FMU, written once.
 *
 * A component's unit (fmu_build/native/component.py writes it) defines the instance struct
 * gw_self, its variable table gw_variables, the defaults and the translated entries gw_build,
 * gw_check_inputs, gw_initialise, gw_advance, gw_evaluate and gw_setup_experiment (each returns
 * 0, or 1 with the Python message in the context), then includes this file. The rules are
 * those of the pythonfmu edition (components/base.py), the one difference being the status of
 * a discarded step (below):
 *
 * - setters store values only: an input marks the outputs and the input check stale, a
 *   parameter the model too; the model is built and the inputs checked when next used;
 * - fmi2DoStep with a bad parameter or input returns fmi2Discard and reports fmi2Terminated
 *   (no shorter step cures it, so a host stops instead of retrying); a model that fails over
 *   the step returns fmi2Discard without fmi2Terminated (a shorter step may succeed); either
 *   leaves the state at the last communication point;
 * - output getters evaluate the model from the present inputs, in Initialization Mode from the
 *   state leaving it will set; after a discarded step, where they cannot, they return the
 *   outputs last evaluated; otherwise a failure is fmi2Error;
 * - every failure is logged naming its cause (while logging is on: fmi2Instantiate's loggingOn,
 *   then fmi2SetDebugLogging) and printed on stderr once, until a call succeeds;
 * - the FMU state is the instance struct and its flags, copied and serialised as bytes.
 */
#include <stddef.h>
#include "fmi2Functions.h"

enum { GW_REAL = 'R', GW_INTEGER = 'I', GW_BOOLEAN = 'B', GW_STRING = 'S' };
enum { GW_PARAMETER = 'P', GW_INPUT = 'U', GW_OUTPUT = 'Y' };

typedef struct {
    fmi2ValueReference vr;
    char type, causality;
    size_t offset;   /* parameters and inputs: the field in gw_self */
    int output;      /* outputs: the index in the evaluated outputs */
    const char *name;
} gw_variable;

static const gw_variable gw_variables[GW_N_VARIABLES]; /* the unit defines it after this file */

typedef struct {             /* what an FMU state holds: everything that evolves */
    gw_self self;
    double outputs[GW_N_OUTPUTS + 1], last_valid[GW_N_OUTPUTS + 1];
    bool built, checked, evaluated, have_last_valid, discarded, initialising, terminated;
    double time;
} gw_state;

typedef struct {
    gw_state state;
    gw_ctx ctx;
    char *instance_name;
    fmi2CallbackFunctions callbacks;
    bool logging;
    char printed[GW_MESSAGE_SIZE];
} gw_instance;

static void gw_report(gw_instance *c, fmi2Status status, const char *message) {
    if (c->callbacks.logger && c->logging)  /* fmi2Instantiate's loggingOn, fmi2SetDebugLogging */
        c->callbacks.logger(c->callbacks.componentEnvironment, c->instance_name, status,
                            "logStatusError", "%s: %s", c->instance_name, message);
    if (strcmp(message, c->printed) != 0) {  /* printed once, until a call succeeds */
        snprintf(c->printed, sizeof c->printed, "%s", message);
        fprintf(stderr, "%s %s: %s\n", GW_CLASS, c->instance_name, message);
    }
}

#define GW_FIELD(c, v, T) ((T *)((char *)&(c)->state.self + (v)->offset))

static const gw_variable *gw_find(fmi2ValueReference vr) {
    size_t i;
    for (i = 0; i < GW_N_VARIABLES; ++i)
        if (gw_variables[i].vr == vr) return &gw_variables[i];
    return NULL;
}

/* Store the text of a String variable (cut to GW_STRING_SIZE - 1 bytes); the law a choosing
 * one names is looked up. */
static int gw_text(gw_instance *c, const gw_variable *v, const char *text) {
    if (text && strlen(text) >= GW_STRING_SIZE) {
        snprintf(c->ctx.message, sizeof c->ctx.message, "the text given to %s is longer than the "
                 "native edition holds (%d bytes); take the python edition", v->name,
                 GW_STRING_SIZE - 1);
        return 1;
    }
    snprintf(GW_FIELD(c, v, char), GW_STRING_SIZE, "%s", text ? text : "");
#ifdef GW_N_CHOICES
    gw_choose(&c->state.self);
#endif
    return 0;
}

static void gw_changed(gw_instance *c, bool parameter) {
    c->state.evaluated = false;
    c->state.checked = false;
    if (parameter) c->state.built = false;
}

/* The model built and the inputs checked: 0, 1 (bad parameter or input; message in ctx). */
static int gw_ready(gw_instance *c) {
    gw_state *s = &c->state;
    if (!s->built) {
        if (gw_build(&c->ctx, &s->self)) return 1;
        s->built = true;
    }
    if (!s->checked) {
        if (gw_check_inputs(&c->ctx, &s->self)) return 1;
        s->checked = true;
    }
    return 0;
}

static int gw_outputs(gw_instance *c) {
    gw_state *s = &c->state;
    size_t i, k;
    if (gw_ready(c)) return 1;
    if (s->initialising && gw_initialise(&c->ctx, &s->self)) return 1;
    if (gw_evaluate(&c->ctx, &s->self, s->outputs)) return 1;
    for (i = 0; i < GW_N_OUTPUTS; ++i)
        if (!isfinite(s->outputs[i])) break;
    if (i == GW_N_OUTPUTS) return 0;
    gw_msg_clear(&c->ctx);  /* base.NOT_FINITE: its dict of the outputs between head and tail */
    gw_msg_text(&c->ctx, GW_MSG_NOT_FINITE_HEAD);
    gw_msg_text(&c->ctx, "{");
    for (i = 0, k = 0; i < GW_N_OUTPUTS; ++i) {
        if (isfinite(s->outputs[i])) continue;
        if (k++) gw_msg_text(&c->ctx, ", ");
        gw_msg_text(&c->ctx, "'");
        gw_msg_text(&c->ctx, gw_output_names[i]);
        gw_msg_text(&c->ctx, "': ");
        gw_msg_repr(&c->ctx, s->outputs[i]);
    }
    gw_msg_text(&c->ctx, "}");
    gw_msg_text(&c->ctx, GW_MSG_NOT_FINITE_TAIL);
    return 1;
}

/* The outputs evaluated, or the last valid ones after a discarded step; fmi2Error else. */
static fmi2Status gw_evaluated(gw_instance *c) {
    gw_state *s = &c->state;
    if (s->evaluated) return fmi2OK;
    if (gw_outputs(c) == 0) {
        memcpy(s->last_valid, s->outputs, sizeof s->outputs);
        s->have_last_valid = s->evaluated = true;
        c->printed[0] = '\0';
        return fmi2OK;
    }
    if (s->discarded && s->have_last_valid) {
        memcpy(s->outputs, s->last_valid, sizeof s->outputs);
        s->evaluated = true;
        return fmi2OK;
    }
    gw_report(c, fmi2Error, c->ctx.message);
    return fmi2Error;
}

/* -- start values from the modelDescription --------------------------------------------
 * As the pythonfmu edition does, an instance starts its parameters and inputs from the start
 * values of the modelDescription.xml beside its resources folder (a tool or `export-ssp` may
 * have changed them there), else from the values the unit was built with. */

/* The file path of the modelDescription of the FMU whose resource URI is ``uri`` (file:///p,
 * file:/p or a plain path, percent escapes decoded) in ``path``: 0, or 1 when there is none. */
static int gw_description_path(const char *uri, char *path, size_t size) {
    size_t n = 0;
    if (!uri) return 1;
    if (strncmp(uri, "file://", 7) == 0) uri += 7;
    else if (strncmp(uri, "file:", 5) == 0) uri += 5;
    if (uri[0] == '/' && uri[1] && uri[2] == ':') ++uri;  /* file:///C:/... */
    for (; *uri && n + 1 < size; ++uri) {
        unsigned code;
        if (uri[0] == '%' && uri[1] && uri[2] && sscanf(uri + 1, "%2x", &code) == 1) {
            path[n++] = (char)code;
            uri += 2;
        } else {
            path[n++] = *uri;
        }
    }
    while (n > 0 && (path[n - 1] == '/' || path[n - 1] == '\\')) --n;
    while (n > 0 && path[n - 1] != '/' && path[n - 1] != '\\') --n;  /* drop "resources" */
    path[n] = '\0';
    if (n == 0 || n + sizeof "modelDescription.xml" > size) return 1;
    strcat(path, "modelDescription.xml");
    return 0;
}

/* The text of attribute ``name`` (name="...", the XML entities of markup decoded) in
 * [from, to) into ``out``: 0, 1 if absent, 2 if longer than ``size`` - 1 bytes. */
static int gw_attribute(const char *from, const char *to, const char *name, char *out,
                        size_t size) {
    static const char *const entities[][2] = {{"&amp;", "&"}, {"&lt;", "<"}, {"&gt;", ">"},
                                              {"&quot;", "\""}, {"&apos;", "'"}};
    size_t length = strlen(name), n = 0, e;
    const char *p, *end;
    for (p = from; p && p + length + 2 < to; ++p) {
        if (strncmp(p, name, length) || p[length] != '=' || p[length + 1] != '"'
            || (p > from && p[-1] != ' ' && p[-1] != '\n' && p[-1] != '\t')) continue;
        p += length + 2;
        end = memchr(p, '"', (size_t)(to - p));
        if (!end) return 1;
        while (p < end) {
            const char *text = p++;
            size_t step = 1;
            for (e = 0; e < sizeof entities / sizeof entities[0]; ++e)
                if (strncmp(text, entities[e][0], strlen(entities[e][0])) == 0) {
                    text = entities[e][1];
                    p += strlen(entities[e][0]) - 1;
                    break;
                }
            if (n + step >= size) return 2;
            out[n++] = *text;
        }
        out[n] = '\0';
        return 0;
    }
    return 1;
}

/* Apply one start value (XML text) to the parameter or input ``v``: 0, or 1 if malformed. */
static int gw_apply_start(gw_instance *c, const gw_variable *v, const char *text) {
    char *end;
    if (v->type == GW_REAL) {
        double value = strtod(text, &end);
        if (end == text || *end) return 1;
        *GW_FIELD(c, v, double) = value;
    } else if (v->type == GW_STRING) {
        return gw_text(c, v, text) ? 2 : 0;
    } else if (v->type == GW_INTEGER) {
        long value = strtol(text, &end, 10);
        if (end == text || *end) return 1;
        *GW_FIELD(c, v, long) = value;
    } else {
        if (strcmp(text, "true") && strcmp(text, "false") && strcmp(text, "1") && strcmp(text, "0"))
            return 1;
        *GW_FIELD(c, v, bool) = strcmp(text, "true") == 0 || strcmp(text, "1") == 0;
    }
    return 0;
}

/* The modelDescription's guid into ``guid`` (empty when the file cannot be read) and its start
 * values applied to the instance: 0, or 1 with the reason in ``message`` (a start value that is
 * not of its variable's type). Without the file the built-in values stay, as for the Python
 * edition instantiated outside an FMU. */
static int gw_read_description(gw_instance *c, const char *resources, char *guid, size_t guid_size,
                               char *message, size_t size) {
    char path[4096], text[GW_STRING_SIZE], name[256];
    const char *at, *end;
    char *xml;
    long length;
    FILE *file;
    int failed = 0, read;
    guid[0] = '\0';
    if (gw_description_path(resources, path, sizeof path) || !(file = fopen(path, "rb")))
        return 0;
    if (fseek(file, 0, SEEK_END) || (length = ftell(file)) < 0 || fseek(file, 0, SEEK_SET)
        || !(xml = (char *)malloc((size_t)length + 1))) {
        fclose(file);
        return 0;
    }
    xml[fread(xml, 1, (size_t)length, file)] = '\0';
    fclose(file);
    if ((at = strstr(xml, "<fmiModelDescription")) && (end = strchr(at, '>'))
        && gw_attribute(at, end, "guid", guid, guid_size))
        guid[0] = '\0';
    for (at = strstr(xml, "<ScalarVariable"); at && !failed; at = strstr(end, "<ScalarVariable")) {
        const gw_variable *v;
        if (!(end = strstr(at, "</ScalarVariable>")) && !(end = strstr(at, "/>"))) break;
        if (gw_attribute(at, end, "valueReference", text, sizeof text)) continue;
        v = gw_find((fmi2ValueReference)strtoul(text, NULL, 10));
        if (!v || v->causality == GW_OUTPUT) continue;
        read = gw_attribute(at, end, "start", text, sizeof text);
        if (read == 1) continue;
        if (read == 2 || (read = gw_apply_start(c, v, text)) != 0) {
            if (gw_attribute(at, end, "name", name, sizeof name)) strcpy(name, "?");
            if (read == 2)
                snprintf(message, size, "%s: the start value of %s is longer than the native "
                         "edition holds (%d bytes); take the python edition", path, name,
                         GW_STRING_SIZE - 1);
            else
                snprintf(message, size, "%s: the start value \"%.200s\" of %s is not of its type",
                         path, text, name);
            failed = 1;
        }
    }
    free(xml);
    return failed;
}

/* -- instance life -------------------------------------------------------------------- */
const char *fmi2GetTypesPlatform(void) { return fmi2TypesPlatform; }
const char *fmi2GetVersion(void) { return fmi2Version; }

/* The guid a host passes must be the modelDescription's beside the resources (a tool or
 * `export-ssp` that changes start values gives the copy a guid of its own), or this build's. */
fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                              fmi2String resources, const fmi2CallbackFunctions *callbacks,
                              fmi2Boolean visible, fmi2Boolean logging) {
    gw_instance *c;
    char described[128], reason[GW_MESSAGE_SIZE];
    const char *why = NULL;
    (void)visible;
    if (type != fmi2CoSimulation || !name) {
        why = "only co-simulation is provided, to a named instance";
    } else if (!(c = (gw_instance *)calloc(1, sizeof *c))
               || !(c->instance_name = (char *)malloc(strlen(name) + 1))) {
        free(c);
        return NULL;
    } else {
        strcpy(c->instance_name, name);
        if (callbacks) c->callbacks = *callbacks;
        c->logging = logging;
        gw_defaults(&c->state.self);
        if (gw_read_description(c, resources, described, sizeof described, reason, sizeof reason))
            why = reason;
        else if (guid && strcmp(guid, described[0] ? described : GW_GUID) != 0)
            why = "the GUID is not this FMU's";
        if (!why) return c;
        free(c->instance_name);
        free(c);
    }
    fprintf(stderr, "%s %s: %s\n", GW_CLASS, name ? name : "?", why);
    if (callbacks && callbacks->logger)
        callbacks->logger(callbacks->componentEnvironment, name ? name : "?", fmi2Error,
                          "logStatusError", "%s", why);
    return NULL;
}

void fmi2FreeInstance(fmi2Component component) {
    gw_instance *c = (gw_instance *)component;
    if (!c) return;
    free(c->ctx.scratch);
    free(c->instance_name);
    free(c);
}

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cats[]) {
    (void)n; (void)cats;
    ((gw_instance *)c)->logging = on;
    return fmi2OK;
}

fmi2Status fmi2SetupExperiment(fmi2Component component, fmi2Boolean tolerance_defined,
                               fmi2Real tolerance, fmi2Real start, fmi2Boolean stop_defined,
                               fmi2Real stop) {
    gw_instance *c = (gw_instance *)component;
    (void)tolerance_defined; (void)stop_defined;
    c->state.time = start;
    if (gw_setup_experiment(&c->ctx, &c->state.self, start, stop, tolerance)) {
        gw_report(c, fmi2Error, c->ctx.message);
        return fmi2Error;
    }
    return fmi2OK;
}

fmi2Status fmi2EnterInitializationMode(fmi2Component component) {
    ((gw_instance *)component)->state.initialising = true;
    return fmi2OK;
}

fmi2Status fmi2ExitInitializationMode(fmi2Component component) {
    gw_instance *c = (gw_instance *)component;
    c->state.initialising = false;
    c->state.evaluated = false;
    if (gw_ready(c) || gw_initialise(&c->ctx, &c->state.self)) {
        gw_report(c, fmi2Error, c->ctx.message);
        return fmi2Error;
    }
    c->printed[0] = '\0';
    return fmi2OK;
}

fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

fmi2Status fmi2Reset(fmi2Component component) {
    gw_instance *c = (gw_instance *)component;
    memset(&c->state, 0, sizeof c->state);
    gw_defaults(&c->state.self);
    c->printed[0] = '\0';
    return fmi2OK;
}

/* -- values --------------------------------------------------------------------------- */

static fmi2Status gw_get(gw_instance *c, const fmi2ValueReference vr[], size_t n, char type,
                         void *values) {
    size_t i;
    for (i = 0; i < n; ++i) {
        const gw_variable *v = gw_find(vr[i]);
        if (!v || v->type != type) {
            gw_report(c, fmi2Error, "unknown value reference or wrong type");
            return fmi2Error;
        }
        if (v->causality == GW_OUTPUT) {
            fmi2Status status = gw_evaluated(c);
            if (status != fmi2OK) return status;
            ((fmi2Real *)values)[i] = c->state.outputs[v->output];
        } else if (type == GW_REAL) {
            ((fmi2Real *)values)[i] = *GW_FIELD(c, v, double);
        } else if (type == GW_INTEGER) {
            ((fmi2Integer *)values)[i] = (fmi2Integer)*GW_FIELD(c, v, long);
        } else {
            ((fmi2Boolean *)values)[i] = *GW_FIELD(c, v, bool) ? fmi2True : fmi2False;
        }
    }
    return fmi2OK;
}

static fmi2Status gw_set(gw_instance *c, const fmi2ValueReference vr[], size_t n, char type,
                         const void *values) {
    size_t i;
    bool parameter = false;
    for (i = 0; i < n; ++i) {
        const gw_variable *v = gw_find(vr[i]);
        if (!v || v->type != type || v->causality == GW_OUTPUT) {
            gw_changed(c, parameter);  /* what the call stored before it failed counts */
            gw_report(c, fmi2Error, "unknown value reference, wrong type or not settable");
            return fmi2Error;
        }
        if (type == GW_REAL) *GW_FIELD(c, v, double) = ((const fmi2Real *)values)[i];
        else if (type == GW_INTEGER) *GW_FIELD(c, v, long) = ((const fmi2Integer *)values)[i];
        else *GW_FIELD(c, v, bool) = ((const fmi2Boolean *)values)[i] != fmi2False;
        parameter |= v->causality == GW_PARAMETER;
    }
    gw_changed(c, parameter);
    return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real v[]) {
    return gw_get((gw_instance *)c, vr, n, GW_REAL, v);
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Integer v[]) {
    return gw_get((gw_instance *)c, vr, n, GW_INTEGER, v);
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Boolean v[]) {
    return gw_get((gw_instance *)c, vr, n, GW_BOOLEAN, v);
}
/* String variables, kept as their text (component.py). */
static const gw_variable *gw_string(gw_instance *c, fmi2ValueReference vr) {
    const gw_variable *v = gw_find(vr);
    if (v && v->type == GW_STRING) return v;
    gw_report(c, fmi2Error, "unknown value reference or not a String variable");
    return NULL;
}

fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2String v[]) {
    size_t i;
    for (i = 0; i < n; ++i) {
        if (!gw_string((gw_instance *)c, vr[i])) return fmi2Error;
        v[i] = GW_FIELD((gw_instance *)c, gw_find(vr[i]), char);
    }
    return fmi2OK;
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real v[]) {
    return gw_set((gw_instance *)c, vr, n, GW_REAL, v);
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer v[]) {
    return gw_set((gw_instance *)c, vr, n, GW_INTEGER, v);
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Boolean v[]) {
    return gw_set((gw_instance *)c, vr, n, GW_BOOLEAN, v);
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2String v[]) {
    size_t i;
    for (i = 0; i < n; ++i) {
        const gw_variable *var = gw_string((gw_instance *)c, vr[i]);
        if (!var || gw_text((gw_instance *)c, var, v[i])) {
            if (i) gw_changed((gw_instance *)c, true);  /* the texts stored before count */
            if (var) gw_report((gw_instance *)c, fmi2Error, ((gw_instance *)c)->ctx.message);
            return fmi2Error;
        }
    }
    if (n) gw_changed((gw_instance *)c, true);
    return fmi2OK;
}

/* -- stepping ------------------------------------------------------------------------- */
fmi2Status fmi2DoStep(fmi2Component component, fmi2Real t, fmi2Real h, fmi2Boolean no_prior) {
    gw_instance *c = (gw_instance *)component;
    gw_state *s = &c->state;
    gw_self saved;
    (void)no_prior;
    s->evaluated = false;
    s->terminated = false;
    if (!(isfinite(h) && h > 0.0)) {
        gw_msg_clear(&c->ctx);
        gw_msg_text(&c->ctx, GW_MSG_STEP_SIZE_HEAD);  /* base.STEP_SIZE */
        gw_msg_repr(&c->ctx, h);
        gw_msg_text(&c->ctx, GW_MSG_STEP_SIZE_TAIL);
        s->terminated = true;
    } else if (gw_ready(c)) {
        s->terminated = true;  /* a bad parameter or input: no shorter step cures it */
    } else {
        saved = s->self;
        if (gw_advance(&c->ctx, &s->self, t, h) == 0) {
            s->discarded = false;
            s->time = t + h;
            c->printed[0] = '\0';
            return fmi2OK;
        }
        s->self = saved;  /* the state stays at the last communication point */
    }
    s->discarded = true;
    gw_report(c, fmi2Discard, c->ctx.message);
    return fmi2Discard;
}

fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }

fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind k, fmi2Status *v) {
    (void)c; (void)k; *v = fmi2OK; return fmi2OK;
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind k, fmi2Real *v) {
    if (k != fmi2LastSuccessfulTime) return fmi2Discard;
    *v = ((gw_instance *)c)->state.time;
    return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind k, fmi2Integer *v) {
    (void)c; (void)k; (void)v; return fmi2Discard;
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind k, fmi2Boolean *v) {
    if (k != fmi2Terminated) return fmi2Discard;
    *v = ((gw_instance *)c)->state.terminated ? fmi2True : fmi2False;
    return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind k, fmi2String *v) {
    (void)c; (void)k; (void)v; return fmi2Discard;
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                       const fmi2Integer order[], const fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    gw_report((gw_instance *)c, fmi2Error, "input derivatives are not supported");
    return fmi2Error;
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                        const fmi2Integer order[], fmi2Real v[]) {
    (void)vr; (void)n; (void)order; (void)v;
    gw_report((gw_instance *)c, fmi2Error, "output derivatives are not supported");
    return fmi2Error;
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu,
                                        const fmi2ValueReference z[], size_t nz,
                                        const fmi2Real du[], fmi2Real dz[]) {
    (void)u; (void)nu; (void)z; (void)nz; (void)du; (void)dz;
    gw_report((gw_instance *)c, fmi2Error, "directional derivatives are not supported");
    return fmi2Error;
}

/* -- FMU state ------------------------------------------------------------------------ */
fmi2Status fmi2GetFMUstate(fmi2Component component, fmi2FMUstate *state) {
    gw_instance *c = (gw_instance *)component;
    gw_state *copy = *state ? (gw_state *)*state : (gw_state *)malloc(sizeof *copy);
    if (!copy) return fmi2Error;
    *copy = c->state;
    *state = copy;
    return fmi2OK;
}

fmi2Status fmi2SetFMUstate(fmi2Component component, fmi2FMUstate state) {
    gw_instance *c = (gw_instance *)component;
    if (!state) return fmi2Error;
    c->state = *(const gw_state *)state;
    c->state.discarded = false;
    gw_changed(c, false);
    return fmi2OK;
}

fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *state) {
    (void)c;
    if (state && *state) { free(*state); *state = NULL; }
    return fmi2OK;
}

fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate state, size_t *size) {
    (void)c; (void)state;
    *size = sizeof(gw_state) + sizeof(GW_GUID);
    return fmi2OK;
}

fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate state, fmi2Byte bytes[], size_t size) {
    if (size < sizeof(gw_state) + sizeof(GW_GUID) || !state) {
        gw_report((gw_instance *)c, fmi2Error, "the buffer for the serialized state is too small");
        return fmi2Error;
    }
    memcpy(bytes, GW_GUID, sizeof(GW_GUID));
    memcpy(bytes + sizeof(GW_GUID), state, sizeof(gw_state));
    return fmi2OK;
}

fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte bytes[], size_t size,
                                   fmi2FMUstate *state) {
    if (size != sizeof(gw_state) + sizeof(GW_GUID) || memcmp(bytes, GW_GUID, sizeof(GW_GUID))) {
        gw_report((gw_instance *)c, fmi2Error, "the serialized state is not one of this FMU");
        return fmi2Error;
    }
    if (!*state && !(*state = malloc(sizeof(gw_state)))) return fmi2Error;
    memcpy(*state, bytes + sizeof(GW_GUID), sizeof(gw_state));
    return fmi2OK;
}
