/* tests/footprint_case.h - the spot light over a floor whose footprint (chapter 6) both
   tests/test_sampling.c and the Mitsuba harness's shim (tests/crosscheck/chi2_shim.c)
   sample: a lamp 1.5 above the floor y = 0, its 30-degree cone tilted; every cone direction
   meets the floor, so no draw through the lamp's cone fails. No sphere around the patch
   (fogrt__footprint_bound adds it). Include after fogrt.h with FOGRT_IMPLEMENTATION. */
#ifndef FOGRT_TESTS_FOOTPRINT_CASE_H
#define FOGRT_TESTS_FOOTPRINT_CASE_H
static fogrt__footprint footprint_case(void)
{
    fogrt__footprint F;
    memset(&F, 0, sizeof F);
    F.light = fogrt__v(0.0f, 1.5f, 0.0f);
    F.cone = fogrt__frame_from_z(fogrt__normalize(fogrt__v(0.3f, -1.0f, 0.1f)));
    F.one_minus_cos = 1.0f - cosf(30.0f * (FOGRT__PI / 180.0f));
    F.p = fogrt__v(0.5f, 0.0f, -0.5f); F.n = fogrt__v(0.0f, 1.0f, 0.0f);
    F.on = true;
    return F;
}
#endif
