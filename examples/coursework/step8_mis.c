/* Step 8: next-event estimation with multiple importance sampling (paper sections 2.3, 3.4).

   An area light can be found two ways: by light sampling at a vertex, and by the ray that
   BSDF or phase sampling sends from it. Step 7 kept only the first. Here both count, each
   weighted by the power heuristic so that the two weights of a direction sum to one
   (coursework.h, "Steps 7 and 8"). Start from your step 7.

   Check it:  make check-step STEP=8           (pictures in build/coursework/step8_*.png)  */
#include <math.h>
#include "coursework.h"

float cw_mis_weight(float pdf_this, float pdf_other)
{
    /* TODO: the power heuristic (0 when pdf_this is 0) */
    (void)pdf_this; (void)pdf_other;
    return 0.5f;
}

fogrt_vec3 cw_mis_radiance(const fogrt_scene *scene, fogrt_vec3 o, fogrt_vec3 d, fogrt_rng *rng, void *user)
{
    const cw_path_settings *set = (const cw_path_settings *)user;
    fogrt_vec3 L = {0.0f, 0.0f, 0.0f};
    /* TODO: your step 7, with
         each area light's sample weighted by cw_mis_weight(ls.pdf, the BSDF/phase pdf of wi);
         the emission a bounced ray reaches weighted by cw_mis_weight(the pdf its direction was
         drawn with, fogrt_scene_light_pdf(scene, the vertex it left, &hit, &sf)) */
    (void)scene; (void)o; (void)d; (void)rng; (void)set;
    return L;
}
