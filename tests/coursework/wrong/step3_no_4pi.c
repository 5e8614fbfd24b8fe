/* Wrong step 3: eq. 9 without its 1/(4 pi). Caught by step3.eq9 and step3.phase_integral
   ("integrates to 4 pi"). */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu) { return (1.0f - g * g) / powf(1.0f + g * g - 2.0f * g * mu, 1.5f); }
float cw_sample_hg_mu(float g, float u) { return fogrt_sample_hg_mu(g, u); }
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2) { return fogrt_sample_hg(g, wo, u1, u2, 0); }
