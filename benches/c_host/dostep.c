/* A minimal FMI 2.0 Co-Simulation host in C: loads the WheelRailContact FMU's shared
 * library, sets the normal model and the wheel loads, and times N calls of fmi2DoStep.
 *
 * Usage: dostep LIB GUID RESOURCE_URI VR_NORMALMODEL MODEL VR_QLEFT VR_QRIGHT VR_Y STEPS MOVING
 *   MOVING 0: constant inputs (the central case, 78.5 kN per wheel);
 *   MOVING 1: the lateral shift y follows a 3 mm, 1 Hz sine at 1 ms steps, set before each step.
 * Prints the mean wall-clock time per step in microseconds. Built and run by benches/c_host/run.sh. */
#include "fmi_host.h"

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
    Fmi f;
    void *lib = load_fmi(argv[1], &f);

    VR vr_model = (VR)atoi(argv[4]), vr_ql = (VR)atoi(argv[6]), vr_qr = (VR)atoi(argv[7]), vr_y = (VR)atoi(argv[8]);
    int model = atoi(argv[5]), steps = atoi(argv[9]), moving = atoi(argv[10]);
    Callbacks cb = {logger, calloc, free, NULL, NULL};
    Component c = f.instantiate("bench", 1, argv[2], argv[3], &cb, 0, 0);
    if (!c) {
        fprintf(stderr, "fmi2Instantiate failed\n");
        return 1;
    }
    const double h = 1e-3, q = 78500.0;
    CHECK(f.setup(c, 0, 0.0, 0.0, 0, 0.0));
    CHECK(f.set_int(c, &vr_model, 1, &model));
    CHECK(f.enter(c));
    CHECK(f.set_real(c, &vr_ql, 1, &q));
    CHECK(f.set_real(c, &vr_qr, 1, &q));
    CHECK(f.leave(c));
    /* One step outside the timing (first evaluation: cold start). */
    CHECK(f.do_step(c, 0.0, h, 1));
    double t = h;
    double start = now();
    for (int k = 0; k < steps; k++) {
        if (moving) {
            double y = 3e-3 * sin(2.0 * 3.14159265358979323846 * t);
            CHECK(f.set_real(c, &vr_y, 1, &y));
        }
        CHECK(f.do_step(c, t, h, 1));
        t += h;
    }
    double per_step = (now() - start) / steps;
    printf("%.3f\n", per_step * 1e6);
    f.terminate(c);
    f.free_instance(c);
    dlclose(lib);
    return 0;
}
