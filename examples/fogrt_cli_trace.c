/* fogrt_cli_trace.c - `fogrt --trace X,Y[,SAMPLE]`: one pixel sample, event by event.

   A second, private copy of the renderer (FOGRT_STATIC) compiled with FOGRT_TRACE, so that
   the trace hooks exist only here and fogrt's ordinary renders carry none of them. The
   scene comes from the main program's copy: fogrt_scene's layout does not depend on
   FOGRT_TRACE, only the integrator's private settings do. */
#define FOGRT_STATIC
#define FOGRT_TRACE
#define FOGRT_IMPLEMENTATION
#include "fogrt.h"
#include <stdio.h>

int cli_trace_path(const fogrt_scene *scene, const fogrt_render_desc *rd, int width, int height, int x, int y,
                   uint32_t sample, FILE *out);

typedef struct trace_out { FILE *f; int events; } trace_out;

#ifndef FOGRT_MINIMAL
static void print_event(const fogrt_trace_event *e, void *user)
{
    trace_out *t = (trace_out *)user;
    char line[768];
    fogrt_trace_describe(e, line, sizeof line);
    if (e->kind == FOGRT_TRACE_END || e->kind == FOGRT_TRACE_CAMERA)
        fprintf(t->f, "%s\n", line);
    else
        fprintf(t->f, "  [bounce %d] %s\n             throughput (%.4g, %.4g, %.4g)\n", e->bounce, line,
                (double)e->beta.x, (double)e->beta.y, (double)e->beta.z);
    t->events++;
}
#endif

int cli_trace_path(const fogrt_scene *scene, const fogrt_render_desc *rd, int width, int height, int x, int y,
                   uint32_t sample, FILE *out)
{
    trace_out t;
#ifdef FOGRT_MINIMAL   /* the trace is Part II's (D): refused when the flags are read */
    (void)scene; (void)rd; (void)width; (void)height; (void)x; (void)y; (void)sample; (void)out; (void)t;
    return 1;
#else
    t.f = out; t.events = 0;
    fprintf(out, "fogrt --trace: pixel (%d, %d) of %dx%d, sample %u, in the order of Algorithm 1\n",
            x, y, width, height, (unsigned)sample);
    (void)fogrt_trace_path(scene, rd, width, height, x, y, sample, print_event, &t);
    fprintf(out, "(%d events; every '+' line is added to the pixel, and they sum to the sample radiance)\n", t.events);
    return ferror(out) ? 1 : 0;
#endif
}
