/* A minimal FMI 2.0 co-simulation host, as a commercial C tool drives an FMU: dlopen, instantiate,
 * initialise, a fixed number of steps, read outputs, terminate, free, dlclose, exit.
 * Used by `guideway-fmu host-env --check` and the C-host tests; built on demand with the
 * system's C compiler against fmpy's copy of the FMI 2.0 headers (on Windows with
 * LoadLibrary: the tests cross-compile it and run it under wine).
 *
 * usage: c_host BINARY RESOURCE_URI GUID STEP_SIZE STEPS [ARGUMENT ...]
 * an ARGUMENT r:VR=VALUE sets a Real and s:VR=TEXT a String before initialisation; a plain VR is a
 * Real output, printed in one line "t v1 v2 ..." after the last step (%.17g). Exit status 0 when
 * every call returned fmi2OK, 2 when instantiation failed, 3 when a later call failed, 1 on bad
 * usage. The FMU logs to stderr, unless the environment sets C_HOST_LOGGING=0. The stepping loop's
 * wall time goes to stderr as "c_host: N steps in S s". */
#ifdef _WIN32
#include <windows.h>
#define dlopen(path, mode) ((void *)LoadLibraryA(path))
#define dlsym(library, name) ((void *)GetProcAddress((HMODULE)(library), name))
#define dlclose(library) FreeLibrary((HMODULE)(library))
#define dlerror() "LoadLibrary failed"
#else
#include <dlfcn.h>
#endif
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "fmi2Functions.h"

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    va_list args;
    (void)env;
    fprintf(stderr, "[%s] status %d %s: ", instance ? instance : "?", (int)status,
            category ? category : "");
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void *symbol(void *library, const char *name)
{
    void *address = dlsym(library, name);
    if (!address) {
        fprintf(stderr, "c_host: the FMU binary has no %s\n", name);
        exit(1);
    }
    return address;
}

#define CHECK(call, what)                                               \
    if ((call) != fmi2OK) {                                             \
        fprintf(stderr, "c_host: %s did not return fmi2OK\n", what);    \
        return 3;                                                       \
    }

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: c_host BINARY RESOURCE_URI GUID STEP_SIZE STEPS [VR ...]\n");
        return 1;
    }
    void *library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "c_host: dlopen failed: %s\n", dlerror());
        return 1;
    }
    fmi2InstantiateTYPE *instantiate = symbol(library, "fmi2Instantiate");
    fmi2SetupExperimentTYPE *setup = symbol(library, "fmi2SetupExperiment");
    fmi2EnterInitializationModeTYPE *enter = symbol(library, "fmi2EnterInitializationMode");
    fmi2ExitInitializationModeTYPE *leave = symbol(library, "fmi2ExitInitializationMode");
    fmi2DoStepTYPE *do_step = symbol(library, "fmi2DoStep");
    fmi2GetRealTYPE *get_real = symbol(library, "fmi2GetReal");
    fmi2SetRealTYPE *set_real = symbol(library, "fmi2SetReal");
    fmi2SetStringTYPE *set_string = symbol(library, "fmi2SetString");
    fmi2TerminateTYPE *terminate = symbol(library, "fmi2Terminate");
    fmi2FreeInstanceTYPE *free_instance = symbol(library, "fmi2FreeInstance");

    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    const char *logging = getenv("C_HOST_LOGGING");
    fmi2Component c = instantiate("c_host", fmi2CoSimulation, argv[3], argv[2], &callbacks,
                                  fmi2False, !(logging && logging[0] == '0'));
    if (!c) {
        fprintf(stderr, "c_host: fmi2Instantiate returned NULL\n");
        return 2;
    }
    double h = atof(argv[4]);
    long steps = atol(argv[5]);
    int n = 0;
    fmi2ValueReference *refs = calloc(argc, sizeof *refs);
    fmi2Real *values = calloc(argc, sizeof *values);
    for (int i = 6; i < argc; ++i) {
        char *end;
        const char *arg = argv[i];
        if ((arg[0] == 'r' || arg[0] == 's') && arg[1] == ':') {
            fmi2ValueReference vr = (fmi2ValueReference)strtoul(arg + 2, &end, 10);
            if (*end != '=') {
                fprintf(stderr, "c_host: bad argument %s (r:VR=VALUE or s:VR=TEXT)\n", arg);
                return 1;
            }
            if (arg[0] == 'r') {
                fmi2Real value = strtod(end + 1, NULL);
                CHECK(set_real(c, &vr, 1, &value), "fmi2SetReal");
            } else {
                fmi2String text = end + 1;
                CHECK(set_string(c, &vr, 1, &text), "fmi2SetString");
            }
        } else {
            refs[n++] = (fmi2ValueReference)strtoul(arg, NULL, 10);
        }
    }

    CHECK(setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), "fmi2SetupExperiment");
    CHECK(enter(c), "fmi2EnterInitializationMode");
    CHECK(leave(c), "fmi2ExitInitializationMode");
    double t = 0.0;
    struct timespec begun, ended;
    timespec_get(&begun, TIME_UTC);
    for (long k = 0; k < steps; ++k, t = k * h) CHECK(do_step(c, t, h, fmi2True), "fmi2DoStep");
    timespec_get(&ended, TIME_UTC);
    fprintf(stderr, "c_host: %ld steps in %.9f s\n", steps,
            (double)(ended.tv_sec - begun.tv_sec) + 1e-9 * (double)(ended.tv_nsec - begun.tv_nsec));
    if (n > 0) CHECK(get_real(c, refs, n, values), "fmi2GetReal");
    printf("%.17g", steps * h);
    for (int i = 0; i < n; ++i) printf(" %.17g", values[i]);
    printf("\n");
    fflush(stdout);
    CHECK(terminate(c), "fmi2Terminate");
    free_instance(c);
    free(refs);
    free(values);
    dlclose(library);
    return 0;
}
