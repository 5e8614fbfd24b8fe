/* Step 5: sampling the BSDFs (paper sections 2.2 and 4.2, eq. 3).

   Three white materials in the local frame (normal +z): diffuse (f = 1/pi, sample cosine-
   weighted), mirror (a delta) and glass (reflect with Schlick's probability F, else refract
   by Snell's law). Each sample returns wi, its pdf, and the weight f |cos| / pdf the path's
   throughput is multiplied by (eq. 3). coursework.h gives the conventions.

   Check it:  make check-step STEP=5           (pictures in build/coursework/step5_*.png)  */
#include <math.h>
#include "coursework.h"

int cw_sample_diffuse(fogrt_vec3 wo, float u1, float u2, cw_bsdf_sample *s)
{
    /* TODO: cosine-weighted direction on wo's side; pdf; weight */
    (void)wo; (void)u1; (void)u2;
    s->wi.x = 0.0f; s->wi.y = 0.0f; s->wi.z = 1.0f;
    s->pdf = 1.0f; s->weight = 1.0f;
    return 1;
}

float cw_diffuse_pdf(fogrt_vec3 wo, fogrt_vec3 wi)
{
    /* TODO: the density of cw_sample_diffuse's directions (per steradian) */
    (void)wo; (void)wi;
    return 0.0f;
}

int cw_sample_mirror(fogrt_vec3 wo, cw_bsdf_sample *s)
{
    /* TODO: the perfect reflection */
    s->wi = wo; s->pdf = 1.0f; s->weight = 1.0f;
    return 1;
}

float cw_fresnel_schlick(float eta, float cos_i)
{
    /* TODO: Schlick's approximation; mind which cosine to use from inside */
    (void)eta; (void)cos_i;
    return 0.0f;
}

int cw_sample_glass(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s)
{
    /* TODO: reflect with probability F, else refract; pdf is the lobe's probability */
    (void)eta; (void)u_lobe;
    s->wi = wo; s->pdf = 1.0f; s->weight = 1.0f;
    return 1;
}
