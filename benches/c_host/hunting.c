/* A C host stepping the WheelRailContact FMU through a hunting motion: the wheelset's lateral
 * shift y = 3 mm sin 2πft and yaw = 1 mrad sin 2πft at f = 5 Hz, with the consistent lateral
 * velocity vy = dy/dt and yaw rate dyaw/dt, 78.5 kN per wheel, kinematic creepages at 30 m/s
 * (omega = 30/0.46 x 1.001), 1 ms steps. Every step meets a new, yawed pose, as in a vehicle run.
 *
 * Usage: hunting LIB GUID RESOURCE_URI MOTION STEPS NORMAL TANGENTIAL PLANAR VR... (MOTION
 *   `hunting`, or `steady` for the central case held constant, y = yaw = 0; NORMAL, TANGENTIAL
 *   the codes of normalModel and tangentialModel, PLANAR 0 or 1; then the value references of
 *   normalModel tangentialModel planarPatch Qleft Qright y yaw vx vy yawRate omega).
 * Prints, in µs per fmi2DoStep (each step timed): the wall clock's mean, median, 99th percentile
 * and largest step, then the thread's CPU time's median and 99th percentile (CPU time leaves out
 * the steps' preemptions by other processes, milliseconds each on a loaded machine: the tail the
 * element itself has). Built and run by benches/c_host/hunting.sh. */
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

static double clock_s(clockid_t id) {
    struct timespec t;
    clock_gettime(id, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int by_value(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#define CHECK(call)                                                                            \
    do {                                                                                       \
        int s_ = (call);                                                                       \
        if (s_ != 0) {                                                                         \
            fprintf(stderr, "%s returned %d at step %d\n", #call, s_, k);                      \
            return 1;                                                                          \
        }                                                                                      \
    } while (0)

enum { NORMAL, TANGENTIAL, PLANAR, QL, QR, Y, YAW, VX, VY, YAWRATE, OMEGA, N_VR };

int main(int argc, char **argv) {
    if (argc != 9 + N_VR) {
        fprintf(stderr, "usage: %s LIB GUID RESOURCE_URI MOTION STEPS NORMAL TANGENTIAL PLANAR "
                        "VR_normalModel VR_tangentialModel VR_planarPatch VR_Qleft VR_Qright VR_y "
                        "VR_yaw VR_vx VR_vy VR_yawRate VR_omega\n", argv[0]);
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
    int (*set_bool)(Component, const VR *, size_t, const int *) = sym(lib, "fmi2SetBoolean");
    int (*set_real)(Component, const VR *, size_t, const double *) = sym(lib, "fmi2SetReal");
    int (*do_step)(Component, double, double, int) = sym(lib, "fmi2DoStep");
    int (*terminate)(Component) = sym(lib, "fmi2Terminate");
    void (*free_instance)(Component) = sym(lib, "fmi2FreeInstance");

    int steady = argv[4][0] == 's';
    int steps = atoi(argv[5]);
    int normal = atoi(argv[6]), tangential = atoi(argv[7]), planar = atoi(argv[8]);
    VR vr[N_VR];
    for (int i = 0; i < N_VR; i++) vr[i] = (VR)atoi(argv[9 + i]);
    if (steps < 1) return 2;
    double *times = malloc(sizeof(double) * (size_t)steps);
    double *cpu = malloc(sizeof(double) * (size_t)steps);
    if (!times || !cpu) return 2;

    Callbacks cb = {logger, calloc, free, NULL, NULL};
    Component c = instantiate("hunting", 1, argv[2], argv[3], &cb, 0, 0);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate failed\n");
        return 1;
    }
    const double h = 1e-3, q = 78500.0, v = 30.0, omega = 30.0 / 0.46 * 1.001;
    const double w = 2.0 * 3.14159265358979323846 * 5.0;
    int k = -1;
    CHECK(setup(c, 0, 0.0, 0.0, 0, 0.0));
    CHECK(set_int(c, &vr[NORMAL], 1, &normal));
    CHECK(set_int(c, &vr[TANGENTIAL], 1, &tangential));
    CHECK(set_bool(c, &vr[PLANAR], 1, &planar));
    CHECK(enter(c));
    CHECK(set_real(c, &vr[QL], 1, &q));
    CHECK(set_real(c, &vr[QR], 1, &q));
    CHECK(set_real(c, &vr[VX], 1, &v));
    CHECK(set_real(c, &vr[OMEGA], 1, &omega));
    CHECK(leave(c));
    /* One step outside the timing (first evaluation: cold start). */
    CHECK(do_step(c, 0.0, h, 1));
    double t = h;
    for (k = 0; k < steps; k++) {
        double start = clock_s(CLOCK_MONOTONIC), start_cpu = clock_s(CLOCK_THREAD_CPUTIME_ID);
        if (!steady) {
            VR motion[4] = {vr[Y], vr[YAW], vr[VY], vr[YAWRATE]};
            double s = sin(w * t), co = cos(w * t);
            double values[4] = {3e-3 * s, 1e-3 * s, 3e-3 * w * co, 1e-3 * w * co};
            CHECK(set_real(c, motion, 4, values));
        }
        CHECK(do_step(c, t, h, 1));
        cpu[k] = clock_s(CLOCK_THREAD_CPUTIME_ID) - start_cpu;
        times[k] = clock_s(CLOCK_MONOTONIC) - start;
        t += h;
    }
    double sum = 0.0;
    for (int i = 0; i < steps; i++) sum += times[i];
    qsort(times, (size_t)steps, sizeof(double), by_value);
    qsort(cpu, (size_t)steps, sizeof(double), by_value);
    int p99 = (int)ceil(0.99 * steps) - 1;
    printf("%.2f %.2f %.2f %.2f %.2f %.2f\n", 1e6 * sum / steps, 1e6 * times[steps / 2],
           1e6 * times[p99], 1e6 * times[steps - 1], 1e6 * cpu[steps / 2], 1e6 * cpu[p99]);
    free(times);
    free(cpu);
    terminate(c);
    free_instance(c);
    dlclose(lib);
    return 0;
}
