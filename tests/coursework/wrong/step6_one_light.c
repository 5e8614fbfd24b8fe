/* Wrong on purpose (tests/test_coursework.c): one light picked at random and its sample
   multiplied by the number of lights, instead of one sample of every light. Unbiased, so
   the images pass; the contract asks for every light, and step6.every_light sees it. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

/* One light's sample seen from p, with the fog's transmittance over the shadow ray; false
   when it brings nothing (no sample, blocked). */
static int w6_one_light(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 p, uint32_t light,
                      fogrt_rng *rng, fogrt_light_sample *ls, float *tr)
{
    fogrt_medium_desc m;
    float u1 = fogrt_rng_float(rng), u2 = fogrt_rng_float(rng), u3 = fogrt_rng_float(rng);
    if (!fogrt_scene_sample_light(scene, light, p, u1, u2, u3, ls)) return 0;
    if (!fogrt_scene_visible(scene, sf, p, ls)) return 0;
    fogrt_scene_get_medium(scene, &m);
    *tr = m.sigma_t > 0.0f ? fogrt_transmittance(m.sigma_t, ls->dist) : 1.0f;
    return 1;
}

fogrt_vec3 cw_direct_surface(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 wo, fogrt_rng *rng)
{
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f}, wo_l, wi_l, f;
    uint32_t i, n = fogrt_scene_light_total(scene);
    wo_l.x = wo.x * sf->s.x + wo.y * sf->s.y + wo.z * sf->s.z;
    wo_l.y = wo.x * sf->t.x + wo.y * sf->t.y + wo.z * sf->t.z;
    wo_l.z = wo.x * sf->n.x + wo.y * sf->n.y + wo.z * sf->n.z;
    if (n) {
        float nl = (float)n;
        i = (uint32_t)(fogrt_rng_float(rng) * nl);
        if (i >= n) i = n - 1;
        fogrt_light_sample ls;
        float tr, k;
        if (!w6_one_light(scene, sf, sf->p, i, rng, &ls, &tr)) return L;
        wi_l.x = ls.wi.x * sf->s.x + ls.wi.y * sf->s.y + ls.wi.z * sf->s.z;
        wi_l.y = ls.wi.x * sf->t.x + ls.wi.y * sf->t.y + ls.wi.z * sf->t.z;
        wi_l.z = ls.wi.x * sf->n.x + ls.wi.y * sf->n.y + ls.wi.z * sf->n.z;
        f = fogrt_bsdf_eval(&sf->material, wo_l, wi_l);          /* 0 behind the surface */
        k = fabsf(wi_l.z) * tr / ls.pdf;
        k *= nl;
        L.x += f.x * ls.Le.x * k; L.y += f.y * ls.Le.y * k; L.z += f.z * ls.Le.z * k;
    }
    return L;
}

fogrt_vec3 cw_direct_fog(const fogrt_scene *scene, fogrt_vec3 p, fogrt_vec3 wo, fogrt_rng *rng)
{
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f};
    fogrt_medium_desc m;
    uint32_t i, n = fogrt_scene_light_total(scene);
    fogrt_scene_get_medium(scene, &m);
    if (n) {
        float nl = (float)n;
        i = (uint32_t)(fogrt_rng_float(rng) * nl);
        if (i >= n) i = n - 1;
        fogrt_light_sample ls;
        float tr, k;
        if (!w6_one_light(scene, NULL, p, i, rng, &ls, &tr)) return L;
        k = fogrt_hg_pdf(m.g, wo, ls.wi) * tr / ls.pdf;
        k *= nl;
        L.x += ls.Le.x * k; L.y += ls.Le.y * k; L.z += ls.Le.z * k;
    }
    return L;
}
