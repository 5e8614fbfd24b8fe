/* Step 6: direct lighting at a vertex by light sampling (paper section 2.3, eq. 3).

   At a scattering vertex, the light arriving straight from the lights is estimated by
   sampling each light once and weighting the sample as eq. 3 does: f Le T / pdf, where f is
   the BSDF times |cos| at a surface and the HG phase function in fog, T the transmittance of
   the shadow ray (eq. 8; 1 without fog), and the sample counts only if nothing blocks it.
   coursework.h describes the building blocks (fogrt_scene_sample_light, fogrt_scene_visible,
   ...) and the conventions.

   Check it:  make check-step STEP=6           (pictures in build/coursework/step6_*.png)  */
#include <math.h>
#include "coursework.h"

fogrt_vec3 cw_direct_surface(const fogrt_scene *scene, const fogrt_surface *sf, fogrt_vec3 wo, fogrt_rng *rng)
{
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f};
    /* TODO: for every light i < fogrt_scene_light_total(scene): sample it from sf->p with three
       numbers from rng; skip it if the sample fails or fogrt_scene_visible says it is blocked;
       add f |cos| Le T / pdf (diffuse f: reflectance / pi when wi is on wo's side of sf->n) */
    (void)scene; (void)sf; (void)wo; (void)rng;
    return L;
}

fogrt_vec3 cw_direct_fog(const fogrt_scene *scene, fogrt_vec3 p, fogrt_vec3 wo, fogrt_rng *rng)
{
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f};
    /* TODO: the same at the fog point p, with the medium's HG phase function instead of f |cos|
       (fogrt_scene_get_medium gives sigma_t and g; sf is NULL for fogrt_scene_visible) */
    (void)scene; (void)p; (void)wo; (void)rng;
    return L;
}
