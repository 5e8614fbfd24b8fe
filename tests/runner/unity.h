/* unity.h - a tiny test runner that is source-compatible with the subset of
 * the Unity C test framework API used by fogrt's tests (see README.md).
 *
 * Written from scratch for fogrt.  A test file looks like:
 *
 *     #include "unity.h"
 *     void setUp(void) {}
 *     void tearDown(void) {}
 *     static void test_add(void) { TEST_ASSERT_EQUAL_INT(4, 2 + 2); }
 *     int main(void) { UNITY_BEGIN(); RUN_TEST(test_add); return UNITY_END(); }
 *
 * A failing assertion prints a report and leaves the current test with
 * longjmp; the next RUN_TEST carries on with the next test. */
#ifndef UNITY_H
#define UNITY_H

/* Same standard headers the real Unity pulls in, so that test files which
 * (accidentally) rely on them build with either runner. */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Provided by every test file; RUN_TEST calls them around each test. */
void setUp(void);
void tearDown(void);

typedef struct {
    jmp_buf     abort_frame;   /* where a failing assertion jumps back to  */
    const char *file;          /* test file name, from UNITY_BEGIN          */
    const char *test_name;     /* current test, from RUN_TEST               */
    int         test_line;     /* line of the RUN_TEST call                 */
    unsigned    tests, failures, ignored;
    int         cur_failed, cur_ignored;
} UnityState;
extern UnityState Unity;

void UnityBegin(const char *file);
int  UnityEnd(void);
void UnityDefaultTestRun(void (*fn)(void), const char *name, int line);

void UnityFail(const char *msg, int line);
void UnityIgnore(const char *msg, int line);
void UnityMessage(const char *msg, int line);
void UnityAbortTest(void);

enum { UNITY_SIGNED, UNITY_UNSIGNED };                 /* number display   */
enum { UNITY_GT = 1, UNITY_LT = 2, UNITY_OR_EQ = 4 };  /* comparisons      */
enum { UNITY_INF, UNITY_NEG_INF, UNITY_NAN, UNITY_DET }; /* float traits   */

void UnityAssertEqualNumber(unsigned long long expected, unsigned long long actual,
                            int display, const char *msg, int line);
void UnityAssertCompare(long long threshold, long long actual, int how,
                        const char *msg, int line);
void UnityAssertFloatWithin(float delta, float expected, float actual,
                            const char *msg, int line);
void UnityAssertDoubleWithin(double delta, double expected, double actual,
                             const char *msg, int line);
void UnityAssertFloatTrait(float actual, int trait, int want, const char *msg, int line);
void UnityAssertFloatArray(const float *expected, const float *actual,
                           unsigned count, const char *msg, int line);
void UnityAssertString(const char *expected, const char *actual,
                       const char *msg, int line);
void UnityAssertMemory(const void *expected, const void *actual, unsigned len,
                       int as_u8_array, const char *msg, int line);

#ifdef __cplusplus
}
#endif

/* Relative tolerances used by TEST_ASSERT_EQUAL_FLOAT / _DOUBLE. */
#ifndef UNITY_FLOAT_PRECISION
#define UNITY_FLOAT_PRECISION (0.00001f)
#endif
#ifndef UNITY_DOUBLE_PRECISION
#define UNITY_DOUBLE_PRECISION (1e-12)
#endif

/* ---- running tests ---------------------------------------------------- */
#define UNITY_BEGIN()  UnityBegin(__FILE__)
#define UNITY_END()    UnityEnd()
#define RUN_TEST(fn)   UnityDefaultTestRun(fn, #fn, __LINE__)

#define TEST_FAIL()                  UnityFail(NULL, __LINE__)
#define TEST_FAIL_MESSAGE(m)         UnityFail((m), __LINE__)
#define TEST_IGNORE()                UnityIgnore(NULL, __LINE__)
#define TEST_IGNORE_MESSAGE(m)       UnityIgnore((m), __LINE__)
#define TEST_MESSAGE(m)              UnityMessage((m), __LINE__)
#define TEST_PASS()                  UnityAbortTest()
#define TEST_PASS_MESSAGE(m)         do { UnityMessage((m), __LINE__); UnityAbortTest(); } while (0)

/* ---- internal building blocks: (arguments..., message) ------------------ */
#define UNITY_CHECK_(cond, m)        do { if (!(cond)) UnityFail((m), __LINE__); } while (0)
#define UNITY_INT_(e, a, m)          UnityAssertEqualNumber((unsigned long long)(long long)(e), \
                                         (unsigned long long)(long long)(a), UNITY_SIGNED, (m), __LINE__)
#define UNITY_UINT_(e, a, m)         UnityAssertEqualNumber((unsigned long long)(e), \
                                         (unsigned long long)(a), UNITY_UNSIGNED, (m), __LINE__)
#define UNITY_UINT32_(e, a, m)       UNITY_UINT_((uint32_t)(e), (uint32_t)(a), m)
#define UNITY_CMP_(how, t, a, m)     UnityAssertCompare((long long)(t), (long long)(a), (how), (m), __LINE__)
#define UNITY_FWITHIN_(d, e, a, m)   UnityAssertFloatWithin((float)(d), (float)(e), (float)(a), (m), __LINE__)
#define UNITY_DWITHIN_(d, e, a, m)   UnityAssertDoubleWithin((double)(d), (double)(e), (double)(a), (m), __LINE__)
#define UNITY_TRAIT_(a, t, want, m)  UnityAssertFloatTrait((float)(a), (t), (want), (m), __LINE__)

/* ---- assertions --------------------------------------------------------- */
#define TEST_ASSERT(c)                          UNITY_CHECK_((c), " Expression Evaluated To FALSE")
#define TEST_ASSERT_MESSAGE(c, m)               UNITY_CHECK_((c), (m))
#define TEST_ASSERT_TRUE(c)                     UNITY_CHECK_((c), " Expected TRUE Was FALSE")
#define TEST_ASSERT_TRUE_MESSAGE(c, m)          UNITY_CHECK_((c), (m))
#define TEST_ASSERT_FALSE(c)                    UNITY_CHECK_(!(c), " Expected FALSE Was TRUE")
#define TEST_ASSERT_FALSE_MESSAGE(c, m)         UNITY_CHECK_(!(c), (m))
#define TEST_ASSERT_NULL(p)                     UNITY_CHECK_((p) == NULL, " Expected NULL")
#define TEST_ASSERT_NULL_MESSAGE(p, m)          UNITY_CHECK_((p) == NULL, (m))
#define TEST_ASSERT_NOT_NULL(p)                 UNITY_CHECK_((p) != NULL, " Expected Non-NULL")
#define TEST_ASSERT_NOT_NULL_MESSAGE(p, m)      UNITY_CHECK_((p) != NULL, (m))
#define TEST_ASSERT_NOT_EQUAL(e, a)             UNITY_CHECK_((e) != (a), " Expected Not-Equal")
#define TEST_ASSERT_NOT_EQUAL_MESSAGE(e, a, m)  UNITY_CHECK_((e) != (a), (m))

#define TEST_ASSERT_EQUAL(e, a)                   UNITY_INT_(e, a, NULL)
#define TEST_ASSERT_EQUAL_MESSAGE(e, a, m)        UNITY_INT_(e, a, m)
#define TEST_ASSERT_EQUAL_INT(e, a)               UNITY_INT_(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT_MESSAGE(e, a, m)    UNITY_INT_(e, a, m)
#define TEST_ASSERT_EQUAL_INT64(e, a)             UNITY_INT_(e, a, NULL)
#define TEST_ASSERT_EQUAL_INT64_MESSAGE(e, a, m)  UNITY_INT_(e, a, m)
#define TEST_ASSERT_EQUAL_UINT(e, a)              UNITY_UINT_(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT_MESSAGE(e, a, m)   UNITY_UINT_(e, a, m)
#define TEST_ASSERT_EQUAL_UINT64(e, a)            UNITY_UINT_(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT64_MESSAGE(e, a, m) UNITY_UINT_(e, a, m)
#define TEST_ASSERT_EQUAL_UINT32(e, a)            UNITY_UINT32_(e, a, NULL)
#define TEST_ASSERT_EQUAL_UINT32_MESSAGE(e, a, m) UNITY_UINT32_(e, a, m)

/* Note Unity's argument order: the threshold comes first. */
#define TEST_ASSERT_GREATER_THAN(t, a)                 UNITY_CMP_(UNITY_GT, t, a, NULL)
#define TEST_ASSERT_GREATER_THAN_MESSAGE(t, a, m)      UNITY_CMP_(UNITY_GT, t, a, m)
#define TEST_ASSERT_LESS_THAN(t, a)                    UNITY_CMP_(UNITY_LT, t, a, NULL)
#define TEST_ASSERT_LESS_THAN_MESSAGE(t, a, m)         UNITY_CMP_(UNITY_LT, t, a, m)
#define TEST_ASSERT_GREATER_OR_EQUAL(t, a)             UNITY_CMP_(UNITY_GT | UNITY_OR_EQ, t, a, NULL)
#define TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(t, a, m)  UNITY_CMP_(UNITY_GT | UNITY_OR_EQ, t, a, m)
#define TEST_ASSERT_LESS_OR_EQUAL(t, a)                UNITY_CMP_(UNITY_LT | UNITY_OR_EQ, t, a, NULL)
#define TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(t, a, m)     UNITY_CMP_(UNITY_LT | UNITY_OR_EQ, t, a, m)

/* EQUAL_FLOAT/_DOUBLE allow a difference of |expected| * precision. */
#define TEST_ASSERT_FLOAT_WITHIN(d, e, a)             UNITY_FWITHIN_(d, e, a, NULL)
#define TEST_ASSERT_FLOAT_WITHIN_MESSAGE(d, e, a, m)  UNITY_FWITHIN_(d, e, a, m)
#define TEST_ASSERT_EQUAL_FLOAT(e, a)                 UNITY_FWITHIN_((float)(e) * UNITY_FLOAT_PRECISION, e, a, NULL)
#define TEST_ASSERT_EQUAL_FLOAT_MESSAGE(e, a, m)      UNITY_FWITHIN_((float)(e) * UNITY_FLOAT_PRECISION, e, a, m)
#define TEST_ASSERT_DOUBLE_WITHIN(d, e, a)            UNITY_DWITHIN_(d, e, a, NULL)
#define TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(d, e, a, m) UNITY_DWITHIN_(d, e, a, m)
#define TEST_ASSERT_EQUAL_DOUBLE(e, a)                UNITY_DWITHIN_((double)(e) * UNITY_DOUBLE_PRECISION, e, a, NULL)
#define TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(e, a, m)     UNITY_DWITHIN_((double)(e) * UNITY_DOUBLE_PRECISION, e, a, m)

#define TEST_ASSERT_FLOAT_IS_INF(a)                         UNITY_TRAIT_(a, UNITY_INF, 1, NULL)
#define TEST_ASSERT_FLOAT_IS_INF_MESSAGE(a, m)              UNITY_TRAIT_(a, UNITY_INF, 1, m)
#define TEST_ASSERT_FLOAT_IS_NOT_INF(a)                     UNITY_TRAIT_(a, UNITY_INF, 0, NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_INF_MESSAGE(a, m)          UNITY_TRAIT_(a, UNITY_INF, 0, m)
#define TEST_ASSERT_FLOAT_IS_NEG_INF(a)                     UNITY_TRAIT_(a, UNITY_NEG_INF, 1, NULL)
#define TEST_ASSERT_FLOAT_IS_NEG_INF_MESSAGE(a, m)          UNITY_TRAIT_(a, UNITY_NEG_INF, 1, m)
#define TEST_ASSERT_FLOAT_IS_NOT_NEG_INF(a)                 UNITY_TRAIT_(a, UNITY_NEG_INF, 0, NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_NEG_INF_MESSAGE(a, m)      UNITY_TRAIT_(a, UNITY_NEG_INF, 0, m)
#define TEST_ASSERT_FLOAT_IS_NAN(a)                         UNITY_TRAIT_(a, UNITY_NAN, 1, NULL)
#define TEST_ASSERT_FLOAT_IS_NAN_MESSAGE(a, m)              UNITY_TRAIT_(a, UNITY_NAN, 1, m)
#define TEST_ASSERT_FLOAT_IS_NOT_NAN(a)                     UNITY_TRAIT_(a, UNITY_NAN, 0, NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_NAN_MESSAGE(a, m)          UNITY_TRAIT_(a, UNITY_NAN, 0, m)
#define TEST_ASSERT_FLOAT_IS_DETERMINATE(a)                 UNITY_TRAIT_(a, UNITY_DET, 1, NULL)
#define TEST_ASSERT_FLOAT_IS_DETERMINATE_MESSAGE(a, m)      UNITY_TRAIT_(a, UNITY_DET, 1, m)
#define TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE(a)             UNITY_TRAIT_(a, UNITY_DET, 0, NULL)
#define TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE_MESSAGE(a, m)  UNITY_TRAIT_(a, UNITY_DET, 0, m)

#define TEST_ASSERT_EQUAL_STRING(e, a)          UnityAssertString((const char *)(e), (const char *)(a), NULL, __LINE__)
#define TEST_ASSERT_EQUAL_STRING_MESSAGE(e, a, m) \
    UnityAssertString((const char *)(e), (const char *)(a), (m), __LINE__)
#define TEST_ASSERT_EQUAL_MEMORY(e, a, len) \
    UnityAssertMemory((const void *)(e), (const void *)(a), (unsigned)(len), 0, NULL, __LINE__)
#define TEST_ASSERT_EQUAL_MEMORY_MESSAGE(e, a, len, m) \
    UnityAssertMemory((const void *)(e), (const void *)(a), (unsigned)(len), 0, (m), __LINE__)
#define TEST_ASSERT_EQUAL_UINT8_ARRAY(e, a, n) \
    UnityAssertMemory((const void *)(e), (const void *)(a), (unsigned)(n), 1, NULL, __LINE__)
#define TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(e, a, n, m) \
    UnityAssertMemory((const void *)(e), (const void *)(a), (unsigned)(n), 1, (m), __LINE__)
#define TEST_ASSERT_EQUAL_FLOAT_ARRAY(e, a, n) \
    UnityAssertFloatArray((const float *)(e), (const float *)(a), (unsigned)(n), NULL, __LINE__)
#define TEST_ASSERT_EQUAL_FLOAT_ARRAY_MESSAGE(e, a, n, m) \
    UnityAssertFloatArray((const float *)(e), (const float *)(a), (unsigned)(n), (m), __LINE__)

#endif /* UNITY_H */
