/* Leak check driver for the TaperedRollerBearing FMU (scripts/leaks.sh).
 *
 *   leaks_driver BINARY.so GUID RESOURCE_URI ITERATIONS
 *
 * Loads the FMU's shared library with dlopen and runs ITERATIONS complete life cycles:
 * instantiate, set up, initialize, step, get, FMU states (get, serialize, deserialize, set,
 * free, and one left for fmi2FreeInstance to free), an error path, terminate, reset, free;
 * plus refused instantiations (wrong GUID, bad resource location). Run under valgrind, no
 * byte may be definitely or indirectly lost. The logger is a real variadic C function. */
#include <dlfcn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

typedef void *C;
typedef void *S;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*alloc)(size_t, size_t);
    void (*free)(void *);
    void (*step_finished)(void *, int);
    void *env;
} Callbacks;

static unsigned long messages = 0;

static void logger(void *env, const char *name, int status, const char *category, const char *message, ...) {
    char buf[4096];
    va_list ap;
    va_start(ap, message);
    vsnprintf(buf, sizeof buf, message, ap);
    va_end(ap);
    (void)env; (void)name; (void)status; (void)category;
    messages++;
}

#define LOAD(var, name)                                              \
    var = dlsym(lib, name);                                          \
    if (!var) { fprintf(stderr, "missing %s\n", name); return 2; }

int main(int argc, char **argv) {
    if (argc != 5) {
        fprintf(stderr, "usage: %s BINARY.so GUID RESOURCE_URI ITERATIONS\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) { fprintf(stderr, "dlopen: %s\n", dlerror()); return 2; }
    C (*instantiate)(const char *, int, const char *, const char *, const Callbacks *, int, int);
    void (*free_instance)(C);
    int (*setup)(C, int, double, double, int, double), (*enter)(C), (*exit_)(C), (*terminate)(C), (*reset)(C);
    int (*set_real)(C, const unsigned *, size_t, const double *), (*get_real)(C, const unsigned *, size_t, double *);
    int (*do_step)(C, double, double, int);
    int (*get_state)(C, S *), (*set_state)(C, S), (*free_state)(C, S *);
    int (*state_size)(C, S, size_t *), (*serialize)(C, S, char *, size_t), (*deserialize)(C, const char *, size_t, S *);
    int (*debug_logging)(C, int, size_t, const char *const *);
    LOAD(instantiate, "fmi2Instantiate");
    LOAD(free_instance, "fmi2FreeInstance");
    LOAD(setup, "fmi2SetupExperiment");
    LOAD(enter, "fmi2EnterInitializationMode");
    LOAD(exit_, "fmi2ExitInitializationMode");
    LOAD(terminate, "fmi2Terminate");
    LOAD(reset, "fmi2Reset");
    LOAD(set_real, "fmi2SetReal");
    LOAD(get_real, "fmi2GetReal");
    LOAD(do_step, "fmi2DoStep");
    LOAD(get_state, "fmi2GetFMUstate");
    LOAD(set_state, "fmi2SetFMUstate");
    LOAD(free_state, "fmi2FreeFMUstate");
    LOAD(state_size, "fmi2SerializedFMUstateSize");
    LOAD(serialize, "fmi2SerializeFMUstate");
    LOAD(deserialize, "fmi2DeSerializeFMUstate");
    LOAD(debug_logging, "fmi2SetDebugLogging");

    Callbacks cb = {logger, calloc, free, NULL, NULL};
    int n = atoi(argv[4]), failures = 0;
    /* Value references: speed 101, Fx 104, Fy 105; outputs frictionTorque 201, Qo.max 217. */
    const unsigned in[3] = {101, 104, 105}, out[2] = {201, 217};
    for (int i = 0; i < n; i++) {
        C c = instantiate("leaks", 1, argv[2], argv[3], &cb, 0, i % 2);
        if (!c) { fprintf(stderr, "iteration %d: fmi2Instantiate returned NULL\n", i); return 1; }
        double u[3] = {300.0 + i, 30000.0, 5000.0 + 100.0 * i}, y[2];
        const char *cats[] = {"logEvents", "no-such-category"};
        debug_logging(c, 1, 2, cats); /* an error, logged */
        failures += setup(c, 0, 0.0, 0.0, 1, 1.0) != 0;
        failures += enter(c) != 0;
        failures += set_real(c, in, 3, u) != 0;
        failures += exit_(c) != 0;
        for (int k = 0; k < 3; k++) {
            u[2] += 1000.0;
            failures += set_real(c, in, 3, u) != 0;
            failures += do_step(c, 1e-3 * k, 1e-3, 1) != 0;
            failures += get_real(c, out, 2, y) != 0;
        }
        S s = NULL, t = NULL, kept = NULL;
        size_t size = 0;
        failures += get_state(c, &s) != 0;
        failures += state_size(c, s, &size) != 0;
        char *bytes = malloc(size);
        failures += serialize(c, s, bytes, size) != 0;
        failures += deserialize(c, bytes, size, &t) != 0;
        failures += deserialize(c, bytes, size / 2, &t) != 3; /* truncated: refused */
        free(bytes);
        failures += set_state(c, t) != 0;
        failures += free_state(c, &s) != 0;
        failures += free_state(c, &t) != 0;
        failures += get_state(c, &kept) != 0; /* freed by fmi2FreeInstance */
        failures += do_step(c, 5.0, 1e-3, 1) != 3; /* wrong time: fmi2Error */
        failures += reset(c) != 0;
        failures += setup(c, 0, 0.0, 0.0, 0, 0.0) != 0;
        failures += enter(c) != 0;
        failures += exit_(c) != 0;
        failures += terminate(c) != 0;
        free_instance(c);
        /* Refused instantiations allocate nothing that stays. */
        failures += instantiate("bad-guid", 1, "{00000000-0000-0000-0000-000000000000}", argv[3], &cb, 0, 0) != NULL;
        failures += instantiate("bad-uri", 1, argv[2], "http://example.com/", &cb, 0, 0) != NULL;
        failures += instantiate("me", 0, argv[2], argv[3], &cb, 0, 0) != NULL;
    }
    dlclose(lib);
    printf("%d life cycles, %lu log messages, %d unexpected statuses\n", n, messages, failures);
    return failures != 0;
}
