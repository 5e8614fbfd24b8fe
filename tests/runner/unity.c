/* unity.c - implementation of the small Unity-compatible runner (unity.h).
 *
 * Output, one line per test:
 *     file:line:test:PASS
 *     file:line:test:FAIL: Expected 1 Was 2        (line of the assertion)
 *     file:line:test:IGNORE: reason
 * and at the end a "N Tests M Failures K Ignored" summary. */
#include "unity.h"

#include <stdlib.h>
#include <string.h>
#include <time.h>

UnityState Unity;

/* ---- printing ----------------------------------------------------------- */

/* Print a character with \n, \r and other control bytes escaped, so that
 * every test result stays on one line. */
static void put_char(char ch)
{
    unsigned char c = (unsigned char)ch;
    if (c >= 32 && c <= 126) putchar(c);
    else if (c == '\n')      fputs("\\n", stdout);
    else if (c == '\r')      fputs("\\r", stdout);
    else                     printf("\\x%02X", c);
}

static void put_text(const char *s)
{
    for (; s != NULL && *s != '\0'; s++) put_char(*s);
}

static void put_float(double x)
{
    if (isnan(x))                  fputs("NaN", stdout);
    else if (isinf(x))             fputs(x < 0 ? "Negative Infinity" : "Infinity", stdout);
    else if (x > -1e-12 && x < 1e-12) putchar('0');
    else                           printf("%.9g", x);
}

/* "file:line:test:" - the start of every result line. */
static void put_location(int line)
{
    put_text(Unity.file);
    printf(":%d:", line);
    put_text(Unity.test_name);
    putchar(':');
}

/* Start a failure report: "file:line:test:FAIL:" (details follow). */
static void fail_begin(int line)
{
    put_location(line);
    fputs("FAIL:", stdout);
}

/* Finish a failure report with the user's message and leave the test. */
static void fail_end(const char *msg)
{
    if (msg != NULL) {
        putchar(':');
        put_text(msg);
    }
    Unity.cur_failed = 1;
    fflush(stdout);
    longjmp(Unity.abort_frame, 1);
}

/* Once a test has failed or been ignored, any further assertion (e.g. in
 * tearDown) just leaves again without reporting anything. */
static void skip_if_done(void)
{
    if (Unity.cur_failed || Unity.cur_ignored)
        longjmp(Unity.abort_frame, 1);
}

/* ---- running tests ------------------------------------------------------ */

void UnityBegin(const char *file)
{
    memset(&Unity, 0, sizeof Unity);
    Unity.file = file;
}

int UnityEnd(void)
{
    printf("\n-----------------------\n");
    /* the trailing space after "Ignored" is there in Unity too */
    printf("%u Tests %u Failures %u Ignored \n", Unity.tests, Unity.failures, Unity.ignored);
    printf("%s\n", Unity.failures == 0 ? "OK" : "FAIL");
    fflush(stdout);
    return (int)Unity.failures;
}

void UnityDefaultTestRun(void (*fn)(void), const char *name, int line)
{
    /* Keep everything in globals: locals may be clobbered by longjmp. */
    static void (*current)(void);
    static clock_t cpu0;
    static int timed = -1;
    if (timed < 0) {
        const char *e = getenv("UNITY_CPU_TIMES");
        timed = e != NULL && *e != '\0' && *e != '0';
    }
    current = fn;
    Unity.test_name = name;
    Unity.test_line = line;
    Unity.tests++;

    cpu0 = clock();
    if (setjmp(Unity.abort_frame) == 0) {
        setUp();
        current();
    }
    if (setjmp(Unity.abort_frame) == 0)
        tearDown();

    if (Unity.cur_ignored) {
        Unity.ignored++;
    } else if (Unity.cur_failed) {
        Unity.failures++;
    } else {
        put_location(Unity.test_line);
        fputs("PASS", stdout);
    }
    putchar('\n');
    /* UNITY_CPU_TIMES=1: the CPU seconds of each test (all its threads), to find the slow ones */
    if (timed) {
        put_location(Unity.test_line);
        printf("CPU %.3f s\n", (double)(clock() - cpu0) / CLOCKS_PER_SEC);
    }
    fflush(stdout);
    Unity.cur_failed = Unity.cur_ignored = 0;
}

void UnityFail(const char *msg, int line)
{
    skip_if_done();
    put_location(line);
    fputs("FAIL", stdout);
    fail_end(msg);
}

void UnityIgnore(const char *msg, int line)
{
    skip_if_done();
    put_location(line);
    fputs("IGNORE", stdout);
    if (msg != NULL) {
        fputs(": ", stdout);
        put_text(msg);
    }
    Unity.cur_ignored = 1;
    fflush(stdout);
    longjmp(Unity.abort_frame, 1);
}

void UnityMessage(const char *msg, int line)
{
    put_location(line);
    fputs("INFO", stdout);
    if (msg != NULL) {
        fputs(": ", stdout);
        put_text(msg);
    }
    putchar('\n');
}

void UnityAbortTest(void)
{
    longjmp(Unity.abort_frame, 1);
}

/* ---- assertions --------------------------------------------------------- */

static void put_number(unsigned long long v, int display)
{
    if (display == UNITY_SIGNED) printf("%lld", (long long)v);
    else                         printf("%llu", v);
}

void UnityAssertEqualNumber(unsigned long long expected, unsigned long long actual,
                            int display, const char *msg, int line)
{
    skip_if_done();
    if (expected == actual) return;
    fail_begin(line);
    fputs(" Expected ", stdout);
    put_number(expected, display);
    fputs(" Was ", stdout);
    put_number(actual, display);
    fail_end(msg);
}

void UnityAssertCompare(long long threshold, long long actual, int how,
                        const char *msg, int line)
{
    int failed = 0;
    skip_if_done();
    if (actual == threshold && !(how & UNITY_OR_EQ)) failed = 1;
    if (actual > threshold && (how & UNITY_LT))      failed = 1;
    if (actual < threshold && (how & UNITY_GT))      failed = 1;
    if (!failed) return;
    fail_begin(line);
    printf(" Expected %lld to be %s than %s%lld", actual,
           (how & UNITY_GT) ? "greater" : "less",
           (how & UNITY_OR_EQ) ? "or equal to " : "", threshold);
    fail_end(msg);
}

/* Unity's closeness rule: equal infinities and two NaNs match; otherwise
 * |actual - expected| <= |delta|, computed in the type under test. */
static int floats_within(float delta, float expected, float actual)
{
    float diff = actual - expected;
    if (isinf(expected) && isinf(actual) && (expected < 0) == (actual < 0)) return 1;
    if (isnan(expected) && isnan(actual)) return 1;
    if (diff < 0)  diff = -diff;
    if (delta < 0) delta = -delta;
    return !(isnan(diff) || isinf(diff) || diff > delta);
}

static int doubles_within(double delta, double expected, double actual)
{
    double diff = actual - expected;
    if (isinf(expected) && isinf(actual) && (expected < 0) == (actual < 0)) return 1;
    if (isnan(expected) && isnan(actual)) return 1;
    if (diff < 0)  diff = -diff;
    if (delta < 0) delta = -delta;
    return !(isnan(diff) || isinf(diff) || diff > delta);
}

static void fail_expected_was_float(int line, double expected, double actual, const char *msg)
{
    fail_begin(line);
    fputs(" Expected ", stdout);
    put_float(expected);
    fputs(" Was ", stdout);
    put_float(actual);
    fail_end(msg);
}

void UnityAssertFloatWithin(float delta, float expected, float actual,
                            const char *msg, int line)
{
    skip_if_done();
    if (!floats_within(delta, expected, actual))
        fail_expected_was_float(line, expected, actual, msg);
}

void UnityAssertDoubleWithin(double delta, double expected, double actual,
                             const char *msg, int line)
{
    skip_if_done();
    if (!doubles_within(delta, expected, actual))
        fail_expected_was_float(line, expected, actual, msg);
}

/* trait: UNITY_INF (+inf only), UNITY_NEG_INF, UNITY_NAN or UNITY_DET
 * (neither inf nor NaN); want: 1 = must have the trait, 0 = must not. */
void UnityAssertFloatTrait(float actual, int trait, int want, const char *msg, int line)
{
    static const char *const names[] = { "Infinity", "Negative Infinity", "NaN", "Determinate" };
    int has;
    skip_if_done();
    switch (trait) {
    case UNITY_INF:     has = isinf(actual) && actual > 0; break;
    case UNITY_NEG_INF: has = isinf(actual) && actual < 0; break;
    case UNITY_NAN:     has = isnan(actual) != 0; break;
    default:            has = !isinf(actual) && !isnan(actual); break;
    }
    if (has == want) return;
    fail_begin(line);
    printf(" Expected %s%s Was ", want ? "" : "Not ", names[trait & 3]);
    put_float(actual);
    fail_end(msg);
}

/* Shared checks of the array assertions: an empty comparison is an error,
 * the same (or two NULL) pointers are equal, one NULL pointer is not. */
static int arrays_trivially_equal(const void *expected, const void *actual,
                                  unsigned count, const char *msg, int line)
{
    if (count == 0) {
        fail_begin(line);
        fputs(" You Asked Me To Compare Nothing, Which Was Pointless.", stdout);
        fail_end(msg);
    }
    if (expected == actual) return 1;
    if (expected == NULL || actual == NULL) {
        fail_begin(line);
        fputs(expected == NULL ? " Expected pointer to be NULL" : " Actual pointer was NULL", stdout);
        fail_end(msg);
    }
    return 0;
}

void UnityAssertFloatArray(const float *expected, const float *actual,
                           unsigned count, const char *msg, int line)
{
    unsigned i;
    skip_if_done();
    if (arrays_trivially_equal(expected, actual, count, msg, line)) return;
    for (i = 0; i < count; i++) {
        if (!floats_within(expected[i] * UNITY_FLOAT_PRECISION, expected[i], actual[i])) {
            fail_begin(line);
            printf(" Element %u", i);
            fputs(" Expected ", stdout);
            put_float(expected[i]);
            fputs(" Was ", stdout);
            put_float(actual[i]);
            fail_end(msg);
        }
    }
}

/* Byte-wise comparison; as_u8_array selects the report style of
 * TEST_ASSERT_EQUAL_UINT8_ARRAY instead of TEST_ASSERT_EQUAL_MEMORY. */
void UnityAssertMemory(const void *expected, const void *actual, unsigned len,
                       int as_u8_array, const char *msg, int line)
{
    const unsigned char *e = (const unsigned char *)expected;
    const unsigned char *a = (const unsigned char *)actual;
    unsigned i;
    skip_if_done();
    if (arrays_trivially_equal(expected, actual, len, msg, line)) return;
    for (i = 0; i < len; i++) {
        if (e[i] == a[i]) continue;
        fail_begin(line);
        if (as_u8_array)
            printf(" Element %u Expected %u Was %u", i, (unsigned)e[i], (unsigned)a[i]);
        else
            printf(" Memory Mismatch. Byte %u Expected 0x%02X Was 0x%02X", i, (unsigned)e[i], (unsigned)a[i]);
        fail_end(msg);
    }
}

static void put_quoted(const char *s)
{
    if (s == NULL) {
        fputs("NULL", stdout);
        return;
    }
    putchar('\'');
    put_text(s);
    putchar('\'');
}

void UnityAssertString(const char *expected, const char *actual,
                       const char *msg, int line)
{
    size_t i = 0;
    skip_if_done();
    if (expected == NULL || actual == NULL) {
        if (expected == actual) return;
    } else {
        while (expected[i] == actual[i] && expected[i] != '\0') i++;
        if (expected[i] == actual[i]) return;
    }
    fail_begin(line);
    fputs(" Expected ", stdout);
    put_quoted(expected);
    fputs(" Was ", stdout);
    put_quoted(actual);
    if (expected != NULL && actual != NULL) {
        printf(" Character %u Expected '", (unsigned)i);
        put_char(expected[i]);
        fputs("' Was '", stdout);
        put_char(actual[i]);
        putchar('\'');
    }
    fail_end(msg);
}
