/* The check counter shared by the C tests: CHECK(cond) counts a pass or prints
 * the failed condition with its line. A test that loops over cases defines
 * CHECK_CASE (an int expression in scope at every CHECK) before including this
 * file, and each failure also prints it. */
#ifndef SK_TEST_CHECK_H
#define SK_TEST_CHECK_H
#include <stdio.h>

static int passed = 0, failed = 0;

#ifdef CHECK_CASE
#define CHECK_PRINT_CASE() printf(" (case %d)", (int)(CHECK_CASE))
#else
#define CHECK_PRINT_CASE() ((void)0)
#endif

#define CHECK(cond)                                           \
    do {                                                      \
        if (cond) {                                           \
            passed++;                                         \
        } else {                                              \
            failed++;                                         \
            printf("FAILED line %d: %s", __LINE__, #cond);    \
            CHECK_PRINT_CASE();                               \
            printf("\n");                                     \
        }                                                     \
    } while (0)

#endif
