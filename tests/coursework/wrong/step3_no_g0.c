/* Wrong step 3: eq. 11 as printed, without the isotropic case: at g = 0 it divides 0 by 0.
   Caught by step3.mu_chi2 g=0 and step3.edges ("g = 0 gave mu = nan"). */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu)
{
    return (1.0f - g * g) / (4.0f * 3.14159265f * powf(1.0f + g * g - 2.0f * g * mu, 1.5f));
}
float cw_sample_hg_mu(float g, float u)
{
    float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return (1.0f + g * g - s * s) / (2.0f * g);
}
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2)
{
    return fogrt_sample_hg(g, wo, u1, u2, 0);
}
