/*
 * The host's logger callback (fmi2CallbackLogger) and memory callbacks.
 *
 * The FMU calls the logger printf-style: `message` is a format and the variadic arguments fill
 * it. Stable Rust cannot define a C-variadic function, so this one formats the message and hands
 * the text to the Rust side through the component environment: a `struct sink` whose first
 * member is the Rust function that records one message (no symbol of the Rust crate is
 * referenced from here, so the link order of the two libraries does not matter).
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

typedef void (*fmi_host_record_fn)(const void *sink, const char *instance, int status,
                                   const char *category, const char *text);

struct fmi_host_sink {
    fmi_host_record_fn record;
};

void fmi_host_logger(void *environment, const char *instance, int status, const char *category,
                     const char *message, ...) {
    const struct fmi_host_sink *sink = (const struct fmi_host_sink *)environment;
    char stack[1024];
    char *heap = NULL;
    const char *text = stack;
    va_list args, again;
    int n;
    if (sink == NULL || sink->record == NULL) {
        return;
    }
    if (message == NULL) {
        sink->record(sink, instance, status, category, "");
        return;
    }
    va_start(args, message);
    va_copy(again, args);
    n = vsnprintf(stack, sizeof stack, message, args);
    if (n < 0) {
        text = "(the FMU's message could not be formatted)";
    } else if ((size_t)n >= sizeof stack) {
        heap = (char *)malloc((size_t)n + 1);
        if (heap != NULL) {
            vsnprintf(heap, (size_t)n + 1, message, again);
            text = heap;
        }
    }
    va_end(again);
    va_end(args);
    sink->record(sink, instance, status, category, text);
    free(heap);
}

void *fmi_host_allocate(size_t count, size_t size) { return calloc(count, size); }

void fmi_host_free(void *p) { free(p); }
