/* Wrong step 3: eq. 11 written with mu measured from wo instead of the propagation
   direction, i.e. g's sign flipped in the sampler (the phase function is right).
   Caught by step3.mu_chi2: "is g's sign flipped?". */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu)
{
    return (1.0f - g * g) / (4.0f * 3.14159265f * powf(1.0f + g * g - 2.0f * g * mu, 1.5f));
}
float cw_sample_hg_mu(float g, float u)
{
    float s;
    if (fabsf(g) < 1e-3f) return 2.0f * u - 1.0f;
    g = -g;
    s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return (1.0f + g * g - s * s) / (2.0f * g);
}
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2)
{
    return fogrt_sample_hg(-g, wo, u1, u2, 0);
}
