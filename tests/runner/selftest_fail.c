/* selftest_fail.c - tests that are meant to fail or be ignored, to check that
 * every assertion family really detects failure and that the counting is
 * right.  The name of each test says what must happen to it:
 *     fail_*   must be reported FAIL
 *     ignore_* must be reported IGNORE
 *     pass_*   must be reported PASS
 * check.sh verifies this, the summary line and the exact text of two lines
 * (marked CHECK-LINE-*) against both this runner and the real Unity.
 * Expected summary: 29 Tests 24 Failures 2 Ignored */
#include "unity.h"

#include <math.h>
#include <string.h>

static int fail_in_setup, fail_in_teardown;
static int body_ran, teardowns;

void setUp(void)
{
    if (fail_in_setup) TEST_FAIL_MESSAGE("setUp failed");
}

void tearDown(void)
{
    teardowns++;
    if (fail_in_teardown) TEST_ASSERT_TRUE_MESSAGE(0, "tearDown failed");
}

/* ---- one failing assertion per family ---------------------------------- */
static void fail_assert(void)         { TEST_ASSERT(1 == 2); }
static void fail_true(void)           { TEST_ASSERT_TRUE_MESSAGE(0, "custom text"); }
static void fail_false(void)          { TEST_ASSERT_FALSE(1); }
static void fail_null(void)           { int x = 0; TEST_ASSERT_NULL(&x); }
static void fail_not_null(void)       { TEST_ASSERT_NOT_NULL(NULL); }
static void fail_equal_int(void)
{
    TEST_ASSERT_EQUAL_INT(1, 2); /* CHECK-LINE-INT */
}
static void fail_int_is_64_bit(void)  { TEST_ASSERT_EQUAL_INT(-1, 0xFFFFFFFFu); }
static void fail_uint64(void)         { TEST_ASSERT_EQUAL_UINT64(1ULL << 40, 1ULL << 41); }
static void fail_not_equal(void)      { TEST_ASSERT_NOT_EQUAL(3, 3); }
static void fail_greater(void)        { TEST_ASSERT_GREATER_THAN(5, 5); }
static void fail_less_or_equal(void)  { TEST_ASSERT_LESS_OR_EQUAL(5, 6); }
static void fail_float_relative(void) { TEST_ASSERT_EQUAL_FLOAT(1.0f, 1.0001f); }
static void fail_float_zero(void)     { TEST_ASSERT_EQUAL_FLOAT(0.0f, 1e-30f); }
static void fail_float_within(void)   { TEST_ASSERT_FLOAT_WITHIN(0.1f, 1.0f, NAN); }
static void fail_double(void)         { TEST_ASSERT_EQUAL_DOUBLE(1.0, 1.0 + 1e-9); }
static void fail_float_not_nan(void)  { TEST_ASSERT_FLOAT_IS_NOT_NAN(NAN); }
static void fail_string(void)
{
    TEST_ASSERT_EQUAL_STRING_MESSAGE("fog", "fig", "strings"); /* CHECK-LINE-STRING */
}
static void fail_memory(void)
{
    const unsigned char a[3] = { 1, 2, 3 }, b[3] = { 1, 2, 4 };
    TEST_ASSERT_EQUAL_MEMORY(a, b, 3);
}
static void fail_uint8_array_null(void)
{
    const unsigned char a[1] = { 1 };
    TEST_ASSERT_EQUAL_UINT8_ARRAY(a, NULL, 1);
}
static void fail_float_array(void)
{
    const float a[2] = { 1.0f, 2.0f }, b[2] = { 1.0f, 2.1f };
    TEST_ASSERT_EQUAL_FLOAT_ARRAY(a, b, 2);
}
static void fail_plain(void)          { TEST_FAIL(); }

/* ---- control flow ------------------------------------------------------- */
static void fail_stops_test(void)
{
    TEST_FAIL_MESSAGE("first failure");
    body_ran = 1; /* must not be reached */
}
static void pass_body_was_skipped(void) { TEST_ASSERT_EQUAL_INT(0, body_ran); }
static void ignore_plain(void)          { TEST_IGNORE(); }
static void ignore_with_message(void)
{
    TEST_IGNORE_MESSAGE("not today");
    TEST_FAIL_MESSAGE("never reached");
}
static void fail_setup(void)            { body_ran = 1; }
static void fail_teardown(void)         { TEST_ASSERT_TRUE(1); }
static void pass_after_setup_failure(void)
{
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, body_ran, "body ran despite failing setUp");
    /* tearDown ran after every earlier test, failed or not */
    TEST_ASSERT_EQUAL_INT(27, teardowns);
}
static void pass_with_message(void)     { TEST_MESSAGE("hello"); }

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(fail_assert);
    RUN_TEST(fail_true);
    RUN_TEST(fail_false);
    RUN_TEST(fail_null);
    RUN_TEST(fail_not_null);
    RUN_TEST(fail_equal_int);
    RUN_TEST(fail_int_is_64_bit);
    RUN_TEST(fail_uint64);
    RUN_TEST(fail_not_equal);
    RUN_TEST(fail_greater);
    RUN_TEST(fail_less_or_equal);
    RUN_TEST(fail_float_relative);
    RUN_TEST(fail_float_zero);
    RUN_TEST(fail_float_within);
    RUN_TEST(fail_double);
    RUN_TEST(fail_float_not_nan);
    RUN_TEST(fail_string);
    RUN_TEST(fail_memory);
    RUN_TEST(fail_uint8_array_null);
    RUN_TEST(fail_float_array);
    RUN_TEST(fail_plain);
    RUN_TEST(fail_stops_test);
    RUN_TEST(pass_body_was_skipped);
    RUN_TEST(ignore_plain);
    RUN_TEST(ignore_with_message);
    fail_in_setup = 1;
    RUN_TEST(fail_setup);
    fail_in_setup = 0;
    fail_in_teardown = 1;
    RUN_TEST(fail_teardown);
    fail_in_teardown = 0;
    RUN_TEST(pass_after_setup_failure);
    RUN_TEST(pass_with_message);
    return UNITY_END();
}
