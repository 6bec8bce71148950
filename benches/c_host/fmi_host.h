/* What the C hosts of benches/c_host share: the FMI 2.0 types they use, the logger callback and
 * the loading of the FMU's shared library with its functions. */
#ifndef FMI_HOST_H
#define FMI_HOST_H

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

/* The FMI functions the hosts call. */
typedef struct {
    Component (*instantiate)(const char *, int, const char *, const char *, const Callbacks *, int, int);
    int (*setup)(Component, int, double, double, int, double);
    int (*enter)(Component);
    int (*leave)(Component);
    int (*set_int)(Component, const VR *, size_t, const int *);
    int (*set_bool)(Component, const VR *, size_t, const int *);
    int (*set_real)(Component, const VR *, size_t, const double *);
    int (*do_step)(Component, double, double, int);
    int (*terminate)(Component);
    void (*free_instance)(Component);
} Fmi;

/* Opens the FMU's shared library `path` and looks its functions up; exits with 2 on failure. */
static void *load_fmi(const char *path, Fmi *f) {
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        fprintf(stderr, "dlopen: %s\n", dlerror());
        exit(2);
    }
    f->instantiate = sym(lib, "fmi2Instantiate");
    f->setup = sym(lib, "fmi2SetupExperiment");
    f->enter = sym(lib, "fmi2EnterInitializationMode");
    f->leave = sym(lib, "fmi2ExitInitializationMode");
    f->set_int = sym(lib, "fmi2SetInteger");
    f->set_bool = sym(lib, "fmi2SetBoolean");
    f->set_real = sym(lib, "fmi2SetReal");
    f->do_step = sym(lib, "fmi2DoStep");
    f->terminate = sym(lib, "fmi2Terminate");
    f->free_instance = sym(lib, "fmi2FreeInstance");
    return lib;
}

#endif
