/* A C host stepping the WheelRailContact FMU through a hunting motion: the wheelset's lateral
 * shift y = 3 mm sin 2πft and yaw = 1 mrad sin 2πft at f = 5 Hz, with the consistent lateral
 * velocity vy = dy/dt and yaw rate dyaw/dt, 78.5 kN per wheel, kinematic creepages at 30 m/s
 * (omega = 30/0.46 x 1.001), 1 ms steps. Every step meets a new, yawed pose, as in a vehicle run.
 *
 * Usage: hunting LIB GUID RESOURCE_URI MOTION STEPS NORMAL TANGENTIAL PLANAR WEAR VR...
 *   (MOTION `hunting`, or `steady` for the central case held constant, y = yaw = 0; NORMAL,
 *   TANGENTIAL, WEAR the codes of normalModel, tangentialModel and wearModel, PLANAR 0 or 1;
 *   then the value references of normalModel tangentialModel planarPatch wearModel Qleft Qright
 *   y yaw vx vy yawRate omega).
 * Prints, in µs per fmi2DoStep (each step timed): the wall clock's mean, median, 99th percentile
 * and largest step, then the thread's CPU time's median and 99th percentile (CPU time leaves out
 * the steps' preemptions by other processes, milliseconds each on a loaded machine: the tail the
 * element itself has). Built and run by benches/c_host/hunting.sh. */
#include "fmi_host.h"

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

enum { NORMAL, TANGENTIAL, PLANAR, WEAR, QL, QR, Y, YAW, VX, VY, YAWRATE, OMEGA, N_VR };

int main(int argc, char **argv) {
    if (argc != 10 + N_VR) {
        fprintf(stderr, "usage: %s LIB GUID RESOURCE_URI MOTION STEPS NORMAL TANGENTIAL PLANAR "
                        "WEAR VR_normalModel VR_tangentialModel VR_planarPatch VR_wearModel "
                        "VR_Qleft VR_Qright VR_y VR_yaw VR_vx VR_vy VR_yawRate VR_omega\n",
                argv[0]);
        return 2;
    }
    Fmi f;
    void *lib = load_fmi(argv[1], &f);

    int steady = argv[4][0] == 's';
    int steps = atoi(argv[5]);
    int normal = atoi(argv[6]), tangential = atoi(argv[7]), planar = atoi(argv[8]);
    int wear = atoi(argv[9]);
    VR vr[N_VR];
    for (int i = 0; i < N_VR; i++) vr[i] = (VR)atoi(argv[10 + i]);
    if (steps < 1) return 2;
    double *times = malloc(sizeof(double) * (size_t)steps);
    double *cpu = malloc(sizeof(double) * (size_t)steps);
    if (!times || !cpu) return 2;

    Callbacks cb = {logger, calloc, free, NULL, NULL};
    Component c = f.instantiate("hunting", 1, argv[2], argv[3], &cb, 0, 0);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate failed\n");
        return 1;
    }
    const double h = 1e-3, q = 78500.0, v = 30.0, omega = 30.0 / 0.46 * 1.001;
    const double w = 2.0 * 3.14159265358979323846 * 5.0;
    int k = -1;
    CHECK(f.setup(c, 0, 0.0, 0.0, 0, 0.0));
    CHECK(f.set_int(c, &vr[NORMAL], 1, &normal));
    CHECK(f.set_int(c, &vr[TANGENTIAL], 1, &tangential));
    CHECK(f.set_bool(c, &vr[PLANAR], 1, &planar));
    CHECK(f.set_int(c, &vr[WEAR], 1, &wear));
    CHECK(f.enter(c));
    CHECK(f.set_real(c, &vr[QL], 1, &q));
    CHECK(f.set_real(c, &vr[QR], 1, &q));
    CHECK(f.set_real(c, &vr[VX], 1, &v));
    CHECK(f.set_real(c, &vr[OMEGA], 1, &omega));
    CHECK(f.leave(c));
    /* One step outside the timing (first evaluation: cold start). */
    CHECK(f.do_step(c, 0.0, h, 1));
    double t = h;
    for (k = 0; k < steps; k++) {
        double start = clock_s(CLOCK_MONOTONIC), start_cpu = clock_s(CLOCK_THREAD_CPUTIME_ID);
        if (!steady) {
            VR motion[4] = {vr[Y], vr[YAW], vr[VY], vr[YAWRATE]};
            double s = sin(w * t), co = cos(w * t);
            double values[4] = {3e-3 * s, 1e-3 * s, 3e-3 * w * co, 1e-3 * w * co};
            CHECK(f.set_real(c, motion, 4, values));
        }
        CHECK(f.do_step(c, t, h, 1));
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
    f.terminate(c);
    f.free_instance(c);
    dlclose(lib);
    return 0;
}
