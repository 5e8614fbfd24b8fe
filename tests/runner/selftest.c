/* selftest.c - every supported assertion, used so that it passes.
 * Must give the same result with tests/runner and with the real Unity
 * (built with -DUNITY_INCLUDE_DOUBLE).  Expected summary: all tests pass. */
#include "unity.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

static int setups, teardowns;

void setUp(void) { setups++; }
void tearDown(void) { teardowns++; }

static void test_booleans(void)
{
    int x = 3;
    TEST_ASSERT(x == 3);
    TEST_ASSERT_MESSAGE(x == 3, "x is three");
    TEST_ASSERT_TRUE(x);
    TEST_ASSERT_TRUE_MESSAGE(x > 2, "x > 2");
    TEST_ASSERT_FALSE(x == 4);
    TEST_ASSERT_FALSE_MESSAGE(0, "zero is false");
}

static void test_pointers(void)
{
    int x = 0;
    const char *none = NULL;
    TEST_ASSERT_NULL(none);
    TEST_ASSERT_NULL_MESSAGE(none, "none");
    TEST_ASSERT_NOT_NULL(&x);
    TEST_ASSERT_NOT_NULL_MESSAGE(&x, "address of x");
}

static void test_integers(void)
{
    TEST_ASSERT_EQUAL(7, 7);
    TEST_ASSERT_EQUAL_MESSAGE(-7, -7, "negative");
    TEST_ASSERT_EQUAL_INT(-1, -1);
    TEST_ASSERT_EQUAL_INT_MESSAGE(42, 6 * 7, "answer");
    TEST_ASSERT_EQUAL_UINT(3u, 3u);
    TEST_ASSERT_EQUAL_UINT_MESSAGE(0u, 0u, "zero");
    /* UINT32 compares the low 32 bits only. */
    TEST_ASSERT_EQUAL_UINT32(0xFFFFFFFFu, -1);
    TEST_ASSERT_EQUAL_UINT32_MESSAGE(0x80000000u, 0x80000000u, "top bit");
    TEST_ASSERT_EQUAL_INT64(-5000000000LL, -5000000000LL);
    TEST_ASSERT_EQUAL_INT64_MESSAGE(INT64_MIN, INT64_MIN, "min");
    TEST_ASSERT_EQUAL_UINT64(UINT64_MAX, UINT64_MAX);
    TEST_ASSERT_EQUAL_UINT64_MESSAGE(1ULL << 63, 1ULL << 63, "top bit");
    TEST_ASSERT_NOT_EQUAL(1, 2);
    TEST_ASSERT_NOT_EQUAL_MESSAGE(1.5, 2.5, "raw != on doubles");
}

static void test_comparisons(void)
{
    /* Unity order: (threshold, actual). */
    TEST_ASSERT_GREATER_THAN(1, 2);
    TEST_ASSERT_GREATER_THAN_MESSAGE(-10, 0, "0 > -10");
    TEST_ASSERT_LESS_THAN(2, 1);
    TEST_ASSERT_LESS_THAN_MESSAGE(0, -10, "-10 < 0");
    TEST_ASSERT_GREATER_OR_EQUAL(5, 5);
    TEST_ASSERT_GREATER_OR_EQUAL_MESSAGE(5, 6, "6 >= 5");
    TEST_ASSERT_LESS_OR_EQUAL(5, 5);
    TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(5, 4, "4 <= 5");
}

static void test_floats(void)
{
    float zero = 0.0f;
    TEST_ASSERT_FLOAT_WITHIN(0.1f, 1.0f, 1.05f);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.5f, -2.0f, -2.4f, "close enough");
    TEST_ASSERT_FLOAT_WITHIN(-0.1f, 1.0f, 0.95f); /* sign of delta ignored */
    /* Relative tolerance: |expected| * 1e-5. */
    TEST_ASSERT_EQUAL_FLOAT(1000.0f, 1000.005f);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(-1.0f, -1.000005f, "relative");
    TEST_ASSERT_EQUAL_FLOAT(0.0f, 0.0f);
    TEST_ASSERT_EQUAL_FLOAT(INFINITY, INFINITY);
    TEST_ASSERT_EQUAL_FLOAT(NAN, NAN); /* Unity treats two NaNs as equal */
    TEST_ASSERT_FLOAT_IS_NAN(zero / zero);
    TEST_ASSERT_FLOAT_IS_NAN_MESSAGE(NAN, "nan");
    TEST_ASSERT_FLOAT_IS_NOT_NAN(1.0f);
    TEST_ASSERT_FLOAT_IS_NOT_NAN_MESSAGE(INFINITY, "inf is not nan");
    TEST_ASSERT_FLOAT_IS_INF(1.0f / zero);
    TEST_ASSERT_FLOAT_IS_INF_MESSAGE(INFINITY, "inf");
    TEST_ASSERT_FLOAT_IS_NOT_INF(1.0f);
    TEST_ASSERT_FLOAT_IS_NOT_INF(-INFINITY); /* Unity: "INF" means +inf only */
    TEST_ASSERT_FLOAT_IS_NOT_INF_MESSAGE(NAN, "nan is not inf");
    TEST_ASSERT_FLOAT_IS_NEG_INF(-INFINITY);
    TEST_ASSERT_FLOAT_IS_NOT_NEG_INF(INFINITY);
    TEST_ASSERT_FLOAT_IS_DETERMINATE(3.0f);
    TEST_ASSERT_FLOAT_IS_DETERMINATE_MESSAGE(-0.0f, "minus zero");
    TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE(NAN);
    TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE_MESSAGE(-INFINITY, "-inf");
}

static void test_doubles(void)
{
    TEST_ASSERT_DOUBLE_WITHIN(1e-9, 1.0, 1.0 + 1e-10);
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE(0.25, 10.0, 9.8, "quarter");
    TEST_ASSERT_EQUAL_DOUBLE(1e6, 1e6 + 1e-7);
    TEST_ASSERT_EQUAL_DOUBLE_MESSAGE(0.1 + 0.2, 0.3, "classic");
}

static void test_strings_and_memory(void)
{
    const unsigned char a[4] = { 1, 2, 3, 250 };
    const unsigned char b[4] = { 1, 2, 3, 250 };
    const float fa[3] = { 1.0f, -2.5f, 1e6f };
    const float fb[3] = { 1.0f, -2.5f, 1e6f + 1.0f };
    char buf[16];
    strcpy(buf, "fog");
    TEST_ASSERT_EQUAL_STRING("fog", buf);
    TEST_ASSERT_EQUAL_STRING_MESSAGE("", "", "empty");
    TEST_ASSERT_EQUAL_STRING(NULL, NULL);
    TEST_ASSERT_EQUAL_MEMORY(a, b, sizeof a);
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(a, a, 2, "same pointer");
    TEST_ASSERT_EQUAL_UINT8_ARRAY(a, b, 4);
    TEST_ASSERT_EQUAL_UINT8_ARRAY_MESSAGE(a, b, 3, "prefix");
    TEST_ASSERT_EQUAL_FLOAT_ARRAY(fa, fb, 3); /* element-wise relative tolerance */
    TEST_ASSERT_EQUAL_FLOAT_ARRAY_MESSAGE(fa, fb, 2, "prefix");
}

static void test_message_and_pass(void)
{
    TEST_MESSAGE("an informational line");
    TEST_PASS();
    TEST_FAIL_MESSAGE("never reached: TEST_PASS ends the test");
}

static void test_setup_teardown_counts(void)
{
    /* 8 earlier tests plus this one have run setUp; tearDown only for 8. */
    TEST_ASSERT_EQUAL_INT(9, setups);
    TEST_ASSERT_EQUAL_INT(8, teardowns);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_booleans);
    RUN_TEST(test_pointers);
    RUN_TEST(test_integers);
    RUN_TEST(test_comparisons);
    RUN_TEST(test_floats);
    RUN_TEST(test_doubles);
    RUN_TEST(test_strings_and_memory);
    RUN_TEST(test_message_and_pass);
    RUN_TEST(test_setup_teardown_counts);
    return UNITY_END();
}
