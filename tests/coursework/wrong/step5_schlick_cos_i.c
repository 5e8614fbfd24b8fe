/* Wrong step 5: Schlick with the incident cosine from inside the glass (|cos_i| instead of
   the transmitted cos_t, and no total internal reflection). Caught by step5.schlick
   ("you used the incident cosine") and step5.glass_dirs / glass_choice. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

int cw_sample_diffuse(fogrt_vec3 wo, float u1, float u2, cw_bsdf_sample *s)
{
    float r = sqrtf(u1), phi = 6.2831853f * u2;
    s->wi.x = r * cosf(phi); s->wi.y = r * sinf(phi); s->wi.z = sqrtf(fmaxf(0.0f, 1.0f - u1));
    if (wo.z < 0.0f) s->wi.z = -s->wi.z;
    s->pdf = fabsf(s->wi.z) / 3.14159265f;
    s->weight = 1.0f;
    return 1;
}
float cw_diffuse_pdf(fogrt_vec3 wo, fogrt_vec3 wi)
{
    return wo.z * wi.z > 0.0f ? fabsf(wi.z) / 3.14159265f : 0.0f;
}
int cw_sample_mirror(fogrt_vec3 wo, cw_bsdf_sample *s)
{
    s->wi.x = -wo.x; s->wi.y = -wo.y; s->wi.z = wo.z;
    s->pdf = 1.0f; s->weight = 1.0f;
    return 1;
}
float cw_fresnel_schlick(float eta, float cos_i)
{
    float r0 = (eta - 1.0f) / (eta + 1.0f), c = cos_i;
    r0 *= r0;
    c = fabsf(c);
    return r0 + (1.0f - r0) * powf(1.0f - c, 5.0f);
}
int cw_sample_glass(float eta, fogrt_vec3 wo, float u_lobe, cw_bsdf_sample *s)
{
    float F = cw_fresnel_schlick(eta, wo.z);
    fogrt_vec3 n = {0.0f, 0.0f, 1.0f}, t;
    int can_refract = fogrt_refract(n, eta, wo, &t);
    if (!can_refract || u_lobe < F) {
        s->wi.x = -wo.x; s->wi.y = -wo.y; s->wi.z = wo.z;
        s->pdf = can_refract ? F : 1.0f;
    } else {
        s->wi = t;
        s->pdf = 1.0f - F;
    }
    s->weight = 1.0f;
    return 1;
}
