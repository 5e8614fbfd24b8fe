/* A/B harness: old fogrt vs new fogrt vs Embree, 1 thread, same rays (bench.c's), same run. */
#define main bench_unused_main
#include "bench/bench.c"
#undef main
#define SIDE_DECL(S) \
  void *S##_build(const float *pos, uint32_t nv, const uint32_t *idx, uint32_t nt); \
  void S##_trace(const void *s, const float *rays, size_t n, bool any, float *t, uint32_t *p); \
  size_t S##_memory(const void *s); void S##_destroy(void *s);
SIDE_DECL(old)
SIDE_DECL(new)
static double wall_s(void) { struct timespec ts; clock_gettime(getenv("AB_WALL") ? CLOCK_MONOTONIC : CLOCK_THREAD_CPUTIME_ID, &ts); return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec; }
int main(int argc, char **argv)
{
    int reps = 7, side = 512, only = -1, mesh_sel = -1, set_sel = -1, a, mi;
    for (a = 1; a < argc; a++) {
        if (!strcmp(argv[a], "--reps")) reps = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--side")) side = atoi(argv[++a]);
        else if (!strcmp(argv[a], "--only")) { a++; only = !strcmp(argv[a], "old") ? 0 : !strcmp(argv[a], "new") ? 1 : 2; }
        else if (!strcmp(argv[a], "--mesh")) { a++; mesh_sel = !strcmp(argv[a], "bunny") ? 0 : 1; }
        else if (!strcmp(argv[a], "--set")) { a++; set_sel = atoi(argv[a]); }
    }
    for (mi = 0; mi < 2; mi++) {
        bench_geometry g;
        fogrt_scene *scene;
        ray_set sets[SET_COUNT];
        float *t_f, *tt[3]; uint32_t *p_f, *pp[3];
        void *so, *sn; bench_embree *e = NULL;
        size_t maxr = 2 * (size_t)side * (size_t)side + 1;
        int k, i;
        if (mesh_sel >= 0 && mesh_sel != mi) continue;
        if (mi == 0) { if (!load_cs184_bunny(&g, side)) make_displaced_sphere(124, 116, "bunny-sized", &g); }
        else make_displaced_sphere(501, 1000, "1M", &g);
        scene = geometry_scene(&g);
        check(fogrt_scene_build(scene, NULL), "build");
        t_f = (float *)xmalloc(sizeof(float) * maxr); p_f = (uint32_t *)xmalloc(sizeof(uint32_t) * maxr);
        for (k = 0; k < 3; k++) { tt[k] = (float *)xmalloc(sizeof(float) * maxr); pp[k] = (uint32_t *)xmalloc(sizeof(uint32_t) * maxr); }
        make_ray_sets(&g, scene, side, sets, t_f, p_f);
        so = (only < 0 || only == 0) ? old_build(g.positions, g.vertex_count, g.indices, g.triangle_count) : NULL;
        sn = (only < 0 || only == 1) ? new_build(g.positions, g.vertex_count, g.indices, g.triangle_count) : NULL;
        if (only < 0 || only == 2) e = bench_embree_create(g.positions, g.vertex_count, g.indices, g.triangle_count, NULL, 0, 1, NULL);
        if (getenv("AB_BUILD")) {
            double bo[15], bn[15];
            int r;
            for (r = 0; r < 9; r++) {
                double t0 = wall_s(); void *x = old_build(g.positions, g.vertex_count, g.indices, g.triangle_count); bo[r] = wall_s() - t0; old_destroy(x);
                t0 = wall_s(); x = new_build(g.positions, g.vertex_count, g.indices, g.triangle_count); bn[r] = wall_s() - t0; new_destroy(x);
            }
            printf("build (scene create+add+build) old %.4f s new %.4f s (medians of 9, alternating)\n", median(bo, 9), median(bn, 9));
        }
        printf("== %s: %u tris; bytes/tri old %.1f new %.1f\n", g.name, g.triangle_count,
               so ? (double)old_memory(so) / g.triangle_count : 0.0, sn ? (double)new_memory(sn) / g.triangle_count : 0.0);
        for (k = 1; k < SET_COUNT; k++) {
            double mr[3][64], rno[64], rne[64], roe[64];
            size_t diff = 0;
            int rep;
            if (set_sel >= 0 && set_sel != k) continue;
            for (rep = 0; rep < reps; rep++) {
                int j;
                for (j = 0; j < 3; j++) {
                    int w = (j + rep) % 3;
                    double t0;
                    if (only >= 0 && w != only) continue;
                    t0 = wall_s();
                    if (w == 0) old_trace(so, sets[k].rays, sets[k].count, sets[k].any_hit, tt[0], pp[0]);
                    else if (w == 1) new_trace(sn, sets[k].rays, sets[k].count, sets[k].any_hit, tt[1], pp[1]);
                    else bench_embree_trace(e, sets[k].rays, sets[k].count, 1, sets[k].any_hit, tt[2], pp[2]);
                    mr[w][rep] = (double)sets[k].count / (wall_s() - t0) * 1e-6;
                }
                rno[rep] = mr[1][rep] / mr[0][rep]; rne[rep] = mr[1][rep] / mr[2][rep]; roe[rep] = mr[0][rep] / mr[2][rep];
            }
            if (only >= 0) { printf("%-7s %zu rays done\n", sets[k].name, sets[k].count); continue; }
            for (i = 0; i < (int)sets[k].count; i++) diff += tt[0][i] != tt[1][i] || pp[0][i] != pp[1][i];
            printf("%-7s %7zu | old %6.2f new %6.2f emb %6.2f Mrays/s | new/old %.3f  old/emb %.3f  new/emb %.3f | old!=new %zu\n",
                   sets[k].name, sets[k].count, median(mr[0], reps), median(mr[1], reps), median(mr[2], reps),
                   median(rno, reps), median(roe, reps), median(rne, reps), diff);
        }
        fflush(stdout);
        if (so) old_destroy(so);
        if (sn) new_destroy(sn);
        if (e) bench_embree_destroy(e);
        fogrt_scene_destroy(scene);
        for (k = 0; k < SET_COUNT; k++) free(sets[k].rays);
        free(t_f); free(p_f); for (k = 0; k < 3; k++) { free(tt[k]); free(pp[k]); }
        geometry_free(&g);
    }
    return 0;
}
