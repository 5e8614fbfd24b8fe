/* Reference solution of step 3 (docs/coursework.md): fogrt's Henyey-Greenstein functions
   behind the kit's signatures. */
#include "../coursework.h"

float cw_hg_phase(float g, float mu) { return fogrt_hg_phase(g, mu); }
float cw_sample_hg_mu(float g, float u) { return fogrt_sample_hg_mu(g, u); }
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2) { return fogrt_sample_hg(g, wo, u1, u2, 0); }
