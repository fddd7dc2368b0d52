/* FMI 2.0 Co-Simulation driver of the portable FMU's tests (tests/portable/test_portable.py).
 * The same source is built twice: with gcc against binaries/linux64/*.so (dlopen) and with
 * x86_64-w64-mingw32-gcc against binaries/win64/*.dll (LoadLibrary, run under wine), so that
 * the two platforms' libraries run exactly the same calls.
 *
 *   driver LIBRARY GUID RESOURCE_URI PLAN OUT
 *
 * PLAN is a text file of whitespace-separated records; every Real is given as the 16 hex
 * digits of its IEEE-754 bits, so that no decimal conversion of either C library is involved:
 *   int VR VALUE          fmi2SetInteger in initialization mode (e.g. fidelity)
 *   real VR BITS          fmi2SetReal in initialization mode (inputs' start values)
 *   ramp VR BITS          a Real input increased by this much before every step
 *   steps N BITS          N steps of size h = BITS from t = 0
 *   outreal N VR...       Real outputs read after every step
 *   outint N VR...        Integer outputs read after every step
 * OUT gets one line per step: the step's index, then the Real outputs as 16 hex digits of their
 * bits, then the Integer outputs in decimal. Exit code 0 when every call returned fmi2OK. */
#include <inttypes.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
typedef HMODULE Lib;
static Lib lib_open(const char *path) { return LoadLibraryA(path); }
static void *lib_sym(Lib lib, const char *name) { return (void *)GetProcAddress(lib, name); }
static void lib_error(const char *path) { fprintf(stderr, "LoadLibrary(%s) failed: error %lu\n", path, (unsigned long)GetLastError()); }
static void lib_close(Lib lib) { FreeLibrary(lib); }
#else
#include <dlfcn.h>
typedef void *Lib;
static Lib lib_open(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(Lib lib, const char *name) { return dlsym(lib, name); }
static void lib_error(const char *path) { fprintf(stderr, "dlopen(%s) failed: %s\n", path, dlerror()); }
static void lib_close(Lib lib) { dlclose(lib); }
#endif

typedef void *C;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*alloc)(size_t, size_t);
    void (*free)(void *);
    void (*step_finished)(void *, int);
    void *env;
} Callbacks;

static void logger(void *env, const char *name, int status, const char *category, const char *message, ...) {
    char buf[4096];
    va_list ap;
    va_start(ap, message);
    vsnprintf(buf, sizeof buf, message, ap);
    va_end(ap);
    (void)env;
    fprintf(stderr, "[%s] status %d %s: %s\n", name, status, category, buf);
}

#define MAXN 4096

static double bits_to_double(const char *hex) {
    uint64_t u = strtoull(hex, NULL, 16);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static uint64_t double_to_bits(double d) {
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    return u;
}

static int failures = 0;
#define CHECK(call)                                                             \
    do {                                                                        \
        int status_ = (call);                                                   \
        if (status_ != 0) {                                                     \
            fprintf(stderr, "%s returned %d (line %d)\n", #call, status_, __LINE__); \
            failures++;                                                         \
        }                                                                       \
    } while (0)

#define LOAD(var, name)                                              \
    do {                                                             \
        *(void **)&var = lib_sym(lib, name);                         \
        if (!var) { fprintf(stderr, "missing %s\n", name); return 2; } \
    } while (0)

int main(int argc, char **argv) {
    if (argc != 6) {
        fprintf(stderr, "usage: %s LIBRARY GUID RESOURCE_URI PLAN OUT\n", argv[0]);
        return 2;
    }
    static unsigned int_vr[MAXN], real_vr[MAXN], ramp_vr[MAXN], out_real[MAXN], out_int[MAXN];
    static int int_val[MAXN];
    static double real_val[MAXN], ramp_val[MAXN], real_out[MAXN];
    static int int_out[MAXN];
    size_t n_int = 0, n_real = 0, n_ramp = 0, n_out_real = 0, n_out_int = 0;
    long steps = 0;
    double h = 0.0;

    FILE *plan = fopen(argv[4], "r");
    if (!plan) { fprintf(stderr, "cannot open plan %s\n", argv[4]); return 2; }
    char key[32], hex[64];
    unsigned vr;
    while (fscanf(plan, "%31s", key) == 1) {
        if (!strcmp(key, "int") && n_int < MAXN && fscanf(plan, "%u %d", &vr, &int_val[n_int]) == 2) {
            int_vr[n_int++] = vr;
        } else if (!strcmp(key, "real") && n_real < MAXN && fscanf(plan, "%u %63s", &vr, hex) == 2) {
            real_vr[n_real] = vr;
            real_val[n_real++] = bits_to_double(hex);
        } else if (!strcmp(key, "ramp") && n_ramp < MAXN && fscanf(plan, "%u %63s", &vr, hex) == 2) {
            ramp_vr[n_ramp] = vr;
            ramp_val[n_ramp++] = bits_to_double(hex);
        } else if (!strcmp(key, "steps") && fscanf(plan, "%ld %63s", &steps, hex) == 2) {
            h = bits_to_double(hex);
        } else if (!strcmp(key, "outreal") && fscanf(plan, "%zu", &n_out_real) == 1 && n_out_real <= MAXN) {
            for (size_t i = 0; i < n_out_real; i++)
                if (fscanf(plan, "%u", &out_real[i]) != 1) { fprintf(stderr, "bad outreal\n"); return 2; }
        } else if (!strcmp(key, "outint") && fscanf(plan, "%zu", &n_out_int) == 1 && n_out_int <= MAXN) {
            for (size_t i = 0; i < n_out_int; i++)
                if (fscanf(plan, "%u", &out_int[i]) != 1) { fprintf(stderr, "bad outint\n"); return 2; }
        } else {
            fprintf(stderr, "bad plan record `%s`\n", key);
            return 2;
        }
    }
    fclose(plan);

    Lib lib = lib_open(argv[1]);
    if (!lib) { lib_error(argv[1]); return 2; }
    C (*instantiate)(const char *, int, const char *, const char *, const Callbacks *, int, int);
    void (*free_instance)(C);
    int (*setup)(C, int, double, double, int, double), (*enter)(C), (*exit_)(C), (*terminate)(C);
    int (*set_real)(C, const unsigned *, size_t, const double *), (*get_real)(C, const unsigned *, size_t, double *);
    int (*set_int)(C, const unsigned *, size_t, const int *), (*get_int)(C, const unsigned *, size_t, int *);
    int (*do_step)(C, double, double, int);
    const char *(*version)(void);
    LOAD(instantiate, "fmi2Instantiate");
    LOAD(free_instance, "fmi2FreeInstance");
    LOAD(setup, "fmi2SetupExperiment");
    LOAD(enter, "fmi2EnterInitializationMode");
    LOAD(exit_, "fmi2ExitInitializationMode");
    LOAD(terminate, "fmi2Terminate");
    LOAD(set_real, "fmi2SetReal");
    LOAD(get_real, "fmi2GetReal");
    LOAD(set_int, "fmi2SetInteger");
    LOAD(get_int, "fmi2GetInteger");
    LOAD(do_step, "fmi2DoStep");
    LOAD(version, "fmi2GetVersion");
    if (strcmp(version(), "2.0") != 0) { fprintf(stderr, "fmi2GetVersion: %s\n", version()); return 1; }

    Callbacks cb = {logger, calloc, free, NULL, NULL};
    C c = instantiate("portable", 1 /* fmi2CoSimulation */, argv[2], argv[3], &cb, 0, 0);
    if (!c) { fprintf(stderr, "fmi2Instantiate returned NULL (resource URI %s)\n", argv[3]); return 1; }
    CHECK(setup(c, 0, 0.0, 0.0, 1, (double)steps * h));
    CHECK(enter(c));
    if (n_int) CHECK(set_int(c, int_vr, n_int, int_val));
    if (n_real) CHECK(set_real(c, real_vr, n_real, real_val));
    CHECK(exit_(c));

    FILE *out = fopen(argv[5], "w");
    if (!out) { fprintf(stderr, "cannot write %s\n", argv[5]); return 2; }
    double t = 0.0;
    for (long k = 0; k < steps && failures == 0; k++) {
        for (size_t i = 0; i < n_ramp; i++) {
            for (size_t j = 0; j < n_real; j++) {
                if (real_vr[j] == ramp_vr[i]) {
                    real_val[j] += ramp_val[i];
                    CHECK(set_real(c, &real_vr[j], 1, &real_val[j]));
                }
            }
        }
        CHECK(do_step(c, t, h, 1));
        t += h;
        if (n_out_real) CHECK(get_real(c, out_real, n_out_real, real_out));
        if (n_out_int) CHECK(get_int(c, out_int, n_out_int, int_out));
        fprintf(out, "%ld", k);
        for (size_t i = 0; i < n_out_real; i++) fprintf(out, " %016" PRIx64, double_to_bits(real_out[i]));
        for (size_t i = 0; i < n_out_int; i++) fprintf(out, " %d", int_out[i]);
        fprintf(out, "\n");
    }
    fclose(out);
    CHECK(terminate(c));
    free_instance(c);
    lib_close(lib);
    fprintf(stderr, "%ld steps, %zu Real and %zu Integer outputs, %d failed calls\n", steps, n_out_real, n_out_int, failures);
    return failures ? 1 : 0;
}
