/* Reference solution of step 5 (docs/coursework.md): fogrt's BSDF sampler with white
   materials and Schlick's Fresnel, behind the kit's signatures. */
#include <string.h>
#include "../coursework.h"

static int ref5_sample(fogrt_bsdf_type type, float eta, fogrt_vec3 wo, float u_lobe, float u1, float u2,
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
    return ref5_sample(FOGRT_BSDF_DIFFUSE, 1.0f, wo, 0.0f, u1, u2, s);
}
float cw_diffuse_pdf(fogrt_vec3 wo, fogrt_vec3 wi)
{
    fogrt_material_desc m;
    memset(&m, 0, sizeof m);
    m.type = FOGRT_BSDF_DIFFUSE;
    return fogrt_bsdf_pdf(&m, wo, wi);
}
int cw_sample_mirror(fogrt_vec3 wo, cw_bsdf_sample *s) { return ref5_sample(FOGRT_BSDF_MIRROR, 1.0f, wo, 0.0f, 0.0f, 0.0f, s); }
float cw_fresnel_schlick(float eta, float cos_i) { return fogrt_fresnel_schlick(eta, cos_i); }
int cw_sample_glass(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s)
{
    return ref5_sample(FOGRT_BSDF_GLASS, eta, wo, u_lobe, 0.0f, 0.0f, s);
}
