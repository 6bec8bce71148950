/* A minimal FMI 2.0 Co-Simulation host in C: loads the WheelRailContact FMU's shared
 * library, sets the normal model and the wheel loads, and times N calls of fmi2DoStep.
 *
 * Usage: dostep LIB GUID RESOURCE_URI VR_NORMALMODEL MODEL VR_QLEFT VR_QRIGHT VR_Y STEPS MOVING
 *   MOVING 0: constant inputs (the central case, 78.5 kN per wheel);
 *   MOVING 1: the lateral shift y follows a 3 mm, 1 Hz sine at 1 ms steps, set before each step.
 * Prints the mean wall-clock time per step in microseconds. Built and run by benches/c_host/run.sh. */
#define _POSIX_C_SOURCE 199309L
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

typedef void *Component;
typedef unsigned int VR;
typedef struct {
    void (*logger)(void *, const char *, int, const char *, const char *, ...);
    void *(*allocate)(size_t, size_t);
    void (*free)(void *);
    void *step_finished;
    void *env;
} Callbacks;

static void logger(void *env, const char *name, int status, const char *category, const char *msg, ...) {
    va_list args;
    (void)env;
    va_start(args, msg);
    fprintf(stderr, "[%s %d %s] ", name, status, category);
    vfprintf(stderr, msg, args);
    fprintf(stderr, "\n");
    va_end(args);
}

static void *sym(void *lib, const char *name) {
    void *p = dlsym(lib, name);
    if (!p) {
        fprintf(stderr, "missing symbol %s\n", name);
        exit(2);
    }
    return p;
}

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

#define CHECK(call)                                                                            \
    do {                                                                                       \
        int s_ = (call);                                                                       \
        if (s_ != 0) {                                                                         \
            fprintf(stderr, "%s returned %d\n", #call, s_);                                    \
            return 1;                                                                          \
        }                                                                                      \
    } while (0)

int main(int argc, char **argv) {
    if (argc != 11) {
        fprintf(stderr, "usage: %s LIB GUID RESOURCE_URI VR_NORMALMODEL MODEL VR_QLEFT VR_QRIGHT VR_Y STEPS MOVING\n", argv[0]);
        return 2;
    }
    void *lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        return 2;
    }
    Component (*instantiate)(const char *, int, const char *, const char *, const Callbacks *, int, int) =
        sym(lib, "fmi2Instantiate");
    int (*setup)(Component, int, double, double, int, double) = sym(lib, "fmi2SetupExperiment");
    int (*enter)(Component) = sym(lib, "fmi2EnterInitializationMode");
    int (*leave)(Component) = sym(lib, "fmi2ExitInitializationMode");
    int (*set_int)(Component, const VR *, size_t, const int *) = sym(lib, "fmi2SetInteger");
    int (*set_real)(Component, const VR *, size_t, const double *) = sym(lib, "fmi2SetReal");
    int (*do_step)(Component, double, double, int) = sym(lib, "fmi2DoStep");
    int (*terminate)(Component) = sym(lib, "fmi2Terminate");
    void (*free_instance)(Component) = sym(lib, "fmi2FreeInstance");

    VR vr_model = (VR)atoi(argv[4]), vr_ql = (VR)atoi(argv[6]), vr_qr = (VR)atoi(argv[7]), vr_y = (VR)atoi(argv[8]);
    int model = atoi(argv[5]), steps = atoi(argv[9]), moving = atoi(argv[10]);
    Callbacks cb = {logger, calloc, free, NULL, NULL};
    Component c = instantiate("bench", 1, argv[2], argv[3], &cb, 0, 0);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate failed\n");
        return 1;
    }
    const double h = 1e-3, q = 78500.0;
    CHECK(setup(c, 0, 0.0, 0.0, 0, 0.0));
    CHECK(set_int(c, &vr_model, 1, &model));
    CHECK(enter(c));
    CHECK(set_real(c, &vr_ql, 1, &q));
    CHECK(set_real(c, &vr_qr, 1, &q));
    CHECK(leave(c));
    /* One step outside the timing (first evaluation: cold start). */
    CHECK(do_step(c, 0.0, h, 1));
    double t = h;
    double start = now();
    for (int k = 0; k < steps; k++) {
        if (moving) {
            double y = 3e-3 * sin(2.0 * 3.14159265358979323846 * t);
            CHECK(set_real(c, &vr_y, 1, &y));
        }
        CHECK(do_step(c, t, h, 1));
        t += h;
    }
    double per_step = (now() - start) / steps;
    printf("%.3f\n", per_step * 1e6);
    terminate(c);
    free_instance(c);
    dlclose(lib);
    return 0;
}
