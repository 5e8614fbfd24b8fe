/* Wrong on purpose (tests/test_coursework.c): eq. 13's cos theta taken from the ray that
   arrived (wo) instead of the new direction wi: weight f |cos theta_o| / pdf. */
#include <math.h>
#include "../../../examples/coursework/coursework.h"

static fogrt_vec3 w7_cwo_local(const fogrt_surface *sf, fogrt_vec3 w)
{
    fogrt_vec3 l;
    l.x = w.x * sf->s.x + w.y * sf->s.y + w.z * sf->s.z;
    l.y = w.x * sf->t.x + w.y * sf->t.y + w.z * sf->t.z;
    l.z = w.x * sf->n.x + w.y * sf->n.y + w.z * sf->n.z;
    return l;
}
static fogrt_vec3 w7_cwo_world(const fogrt_surface *sf, fogrt_vec3 l)
{
    fogrt_vec3 w;
    w.x = l.x * sf->s.x + l.y * sf->t.x + l.z * sf->n.x;
    w.y = l.x * sf->s.y + l.y * sf->t.y + l.z * sf->n.y;
    w.z = l.x * sf->s.z + l.y * sf->t.z + l.z * sf->n.z;
    return w;
}

/* Eq. 3 with one sample of every light (step 6) at a surface point (sf) or a fog point. */
static fogrt_vec3 w7_cwo_direct(const fogrt_scene *scene, const fogrt_medium_desc *m, const fogrt_surface *sf,
                              fogrt_vec3 p, fogrt_vec3 wo, fogrt_rng *rng)
{
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f}, f;
    uint32_t i, n = fogrt_scene_light_total(scene);
    for (i = 0; i < n; ++i) {
        fogrt_light_sample ls;
        float u1 = fogrt_rng_float(rng), u2 = fogrt_rng_float(rng), u3 = fogrt_rng_float(rng), k;
        if (!fogrt_scene_sample_light(scene, i, p, u1, u2, u3, &ls) || !fogrt_scene_visible(scene, sf, p, &ls)) continue;
        k = (m->sigma_t > 0.0f ? fogrt_transmittance(m->sigma_t, ls.dist) : 1.0f) / ls.pdf;
        if (sf) {
            fogrt_vec3 wi_l = w7_cwo_local(sf, ls.wi);
            f = fogrt_bsdf_eval(&sf->material, w7_cwo_local(sf, wo), wi_l);
            k *= fabsf(wi_l.z);
        } else {
            f.x = f.y = f.z = fogrt_hg_pdf(m->g, wo, ls.wi);
        }
        L.x += f.x * ls.Le.x * k; L.y += f.y * ls.Le.y * k; L.z += f.z * ls.Le.z * k;
    }
    return L;
}

fogrt_vec3 cw_path_radiance(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user)
{
    const cw_path_settings *set = (const cw_path_settings *)user;
    fogrt_medium_desc m;
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f}, beta = {1.0f, 1.0f, 1.0f};
    int depth = 0;
    fogrt_scene_get_medium(scene, &m);
    for (;;) {
        fogrt_hit hit;
        fogrt_surface sf;
        fogrt_vec3 wo, Ld;
        int found = fogrt_scene_intersect(scene, o, d, 0.0f, INFINITY, &hit), in_fog;
        float t_fog = m.sigma_t > 0.0f ? fogrt_sample_exponential(m.sigma_t, fogrt_rng_float(rng)) : INFINITY, q;
        wo.x = -d.x; wo.y = -d.y; wo.z = -d.z;
        in_fog = t_fog < (found ? hit.t : INFINITY);
        if (in_fog) {                                            /* lines 5, 14: a fog particle */
            o.x += d.x * t_fog; o.y += d.y * t_fog; o.z += d.z * t_fog;
            beta.x *= m.albedo.x; beta.y *= m.albedo.y; beta.z *= m.albedo.z;
        } else if (!found) {
            break;                                               /* the ray left the scene */
        } else {                                                 /* lines 8, 18: an object */
            fogrt_scene_surface(scene, o, d, &hit, &sf);
            if (depth == 0 && sf.front) {
                L.x += beta.x * sf.material.emission.x; L.y += beta.y * sf.material.emission.y;
                L.z += beta.z * sf.material.emission.z;
            }
            if (sf.material.reflectance.x + sf.material.reflectance.y + sf.material.reflectance.z <= 0.0f) break;
        }
        if (set->max_depth >= 0 && depth >= set->max_depth) break;            /* line 2: ray depth */
        Ld = w7_cwo_direct(scene, &m, in_fog ? NULL : &sf, in_fog ? o : sf.p, wo, rng);      /* lines 6, 9 */
        L.x += beta.x * Ld.x; L.y += beta.y * Ld.y; L.z += beta.z * Ld.z;
        if (in_fog) {                                            /* lines 15-17: HG, weight 1 */
            float u1 = fogrt_rng_float(rng), u2 = fogrt_rng_float(rng);
            d = fogrt_sample_hg(m.g, wo, u1, u2, NULL);
        } else {                                                 /* lines 19-22: eq. 13 */
            fogrt_bsdf_sample bs;
            float u0 = fogrt_rng_float(rng), u1 = fogrt_rng_float(rng), u2 = fogrt_rng_float(rng);
            if (!fogrt_sample_bsdf(&sf.material, FOGRT_FRESNEL_SCHLICK, w7_cwo_local(&sf, wo), u0, u1, u2, &bs)) break;
            {
                fogrt_vec3 wo_l = w7_cwo_local(&sf, wo), fr = fogrt_bsdf_eval(&sf.material, wo_l, bs.wi);
                float k = fabsf(wo_l.z) / bs.pdf;
                beta.x *= fr.x * k; beta.y *= fr.y * k; beta.z *= fr.z * k;
            }
            d = w7_cwo_world(&sf, bs.wi);
            o = fogrt_surface_offset(scene, &sf, d);
        }
        ++depth;                                                 /* lines 12, 23 */
        if (depth > set->rr_depth) {                             /* line 2: coin flip(p) */
            q = fmaxf(beta.x, fmaxf(beta.y, beta.z));
            if (q > 0.95f) q = 0.95f;
            if (!(fogrt_rng_float(rng) < q)) break;
            beta.x /= q; beta.y /= q; beta.z /= q;
        }
    }
    return L;
}
