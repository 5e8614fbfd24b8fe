/* Wrong on purpose (tests/test_coursework.c): eq. 9 with the sign of 2 g mu flipped, written
   in float: HG with -g. Near the flipped peak float rounding moves the values off the
   double-precision HG(-g) by more than 1e-4, which the hint must allow for. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu)
{
    return (1.0f - g * g) / (4.0f * 3.14159265f * powf(1.0f + g * g + 2.0f * g * mu, 1.5f));
}
float cw_sample_hg_mu(float g, float u) { return fogrt_sample_hg_mu(g, u); }
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2) { return fogrt_sample_hg(g, wo, u1, u2, 0); }
