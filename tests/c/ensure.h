/* Minimal test macros for the Hearth C harness. Each program prints "N passed, M failed". */
#ifndef HEARTH_TEST_ENSURE_H
#define HEARTH_TEST_ENSURE_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int g_passed = 0;
static int g_failed = 0;

#define ENSURE(cond)                                                                       \
    do {                                                                                   \
        if (cond) {                                                                        \
            g_passed++;                                                                    \
        } else {                                                                           \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: ENSURE(%s) failed\n", __FILE__, __LINE__, #cond);      \
        }                                                                                  \
    } while (0)

/* Expects a result code and, for failures, a non-empty thread-local message. */
#define ENSURE_RESULT(call, expected)                                                      \
    do {                                                                                   \
        HearthResult r_ = (call);                                                          \
        if (r_ == (expected)) {                                                            \
            g_passed++;                                                                    \
            if ((expected) != HEARTH_OK) {                                                 \
                char msg_[256];                                                            \
                size_t n_ = hearth_last_error_message(msg_, sizeof msg_);                  \
                ENSURE(n_ > 0 && strlen(msg_) > 0);                                        \
            }                                                                              \
        } else {                                                                           \
            char msg_[256];                                                                \
            hearth_last_error_message(msg_, sizeof msg_);                                  \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: %s returned %s, expected %s (last error: %s)\n",       \
                    __FILE__, __LINE__, #call, hearth_result_name(r_),                     \
                    hearth_result_name(expected), msg_);                                   \
        }                                                                                  \
    } while (0)

#define ENSURE_OK(call) ENSURE_RESULT(call, HEARTH_OK)

#define ENSURE_NEAR(a, b, tol)                                                             \
    do {                                                                                   \
        double a_ = (a), b_ = (b);                                                         \
        if (fabs(a_ - b_) <= (tol)) {                                                      \
            g_passed++;                                                                    \
        } else {                                                                           \
            g_failed++;                                                                    \
            fprintf(stderr, "%s:%d: |%s - %s| = |%g - %g| > %g\n", __FILE__, __LINE__, #a,  \
                    #b, a_, b_, (double)(tol));                                            \
        }                                                                                  \
    } while (0)

static int ensure_report(const char *name) {
    printf("%s: %d passed, %d failed\n", name, g_passed, g_failed);
    return g_failed == 0 ? 0 : 1;
}

#endif
