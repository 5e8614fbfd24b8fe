/* Wrong on purpose (tests/test_coursework.c): eq. 11 run the other way, mu(u) = mu(1 - u),
   as some texts write it (mu falling from +1 at u = 0). The distribution is right; the kit's
   convention is the paper's, and step3.edges says that the convention is what failed. */
#include "../../../examples/coursework/coursework.h"

float cw_hg_phase(float g, float mu) { return fogrt_hg_phase(g, mu); }
float cw_sample_hg_mu(float g, float u) { return fogrt_sample_hg_mu(g, (float)(1.0 - (double)u)); }
fogrt_vec3 cw_sample_hg(float g, fogrt_vec3 wo, float u1, float u2) { return fogrt_sample_hg(g, wo, u1, u2, 0); }
