/* Wrong on purpose (tests/test_coursework.c): glass that refracts with the ratio of entering
   the glass on both sides: leaving it (wo.z < 0) the ratio is not inverted. */
#include <math.h>
#include <string.h>
#include "../../../examples/coursework/coursework.h"

static int w5_eta_sample(fogrt_bsdf_type type, float eta, fogrt_vec3 wo, float u_lobe, float u1, float u2,
                       cw_bsdf_sample *s)
{
    fogrt_material_desc m;
    fogrt_bsdf_sample out;
    memset(&m, 0, sizeof m);
    m.type = type;
    m.reflectance.x = m.reflectance.y = m.reflectance.z = 1.0f;
    m.transmittance = m.reflectance;
    m.ior = eta;
    if (!fogrt_sample_bsdf(&m, FOGRT_FRESNEL_SCHLICK, wo, u_lobe, u1, u2, &out)) return 0;
    s->wi = out.wi;
    s->pdf = out.pdf;
    s->weight = out.weight.x;
    return 1;
}

int cw_sample_diffuse(fogrt_vec3 wo, float u1, float u2, cw_bsdf_sample *s)
{
    return w5_eta_sample(FOGRT_BSDF_DIFFUSE, 1.0f, wo, 0.0f, u1, u2, s);
}
float cw_diffuse_pdf(fogrt_vec3 wo, fogrt_vec3 wi)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    return fogrt_bsdf_pdf(&m, wo, wi);
}
int cw_sample_mirror(fogrt_vec3 wo, cw_bsdf_sample *s) { return w5_eta_sample(FOGRT_BSDF_MIRROR, 1.0f, wo, 0.0f, 0.0f, 0.0f, s); }
float cw_fresnel_schlick(float eta, float cos_i) { return fogrt_fresnel_schlick(eta, cos_i); }
int cw_sample_glass(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s)
{
    float F = fogrt_fresnel_schlick(eta, wo.z), r = 1.0f / eta, ci = fabsf(wo.z), s2, ct;
    if (u_lobe < F) {
        s->wi.x = -wo.x; s->wi.y = -wo.y; s->wi.z = wo.z;
        s->pdf = F; s->weight = 1.0f;
        return 1;
    }
    s2 = r * r * (1.0f - ci * ci);          /* 1/eta on both sides: wrong when leaving */
    ct = sqrtf(fmaxf(0.0f, 1.0f - s2));
    s->wi.x = -r * wo.x; s->wi.y = -r * wo.y; s->wi.z = wo.z > 0.0f ? -ct : ct;
    s->pdf = 1.0f - F; s->weight = 1.0f;
    return 1;
}
