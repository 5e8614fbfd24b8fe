/* fan_mesh.c - writes a "fan": N long thin triangles that all share one vertex, the mesh
   that defeats a BVH of axis-aligned boxes (every triangle's box reaches from the shared
   vertex to the far arc, so near that vertex every box overlaps every other).

   The vertices are bench/fan.h's: vertex 0 at the origin, the others on a far arc spanning
   SPAN degrees (90 by default: most triangles run diagonally, the worst case for
   axis-aligned boxes) in the plane z = 0 (--tilt: z = (x + y) / 2); triangle i is
   (0, i + 1, i + 2).

   Usage: fan_mesh [--span DEG] [--tilt] [--obj] N OUT
     default  a binary little-endian PLY (float x, y, z; faces as uchar count, int indices)
     --obj    an OBJ whose single face is the polygon 1 2 .. N + 2 (a reader that
              triangulates a polygon as a fan from its first corner gets the same N triangles)
   make bench writes its fan with this program (mk/bench.mk).                               */
#include "fan.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void put_u32(unsigned char *b, uint32_t v)
{
    b[0] = (unsigned char)(v & 0xFFu); b[1] = (unsigned char)((v >> 8) & 0xFFu);
    b[2] = (unsigned char)((v >> 16) & 0xFFu); b[3] = (unsigned char)(v >> 24);
}
static void put_f32(unsigned char *b, float f)
{
    uint32_t v;
    memcpy(&v, &f, sizeof v);
    put_u32(b, v);
}
static int write_ply(FILE *f, uint32_t n, double span, int tilt)
{
    unsigned char b[13];
    uint32_t k, nv = n + 2;
    float p[3];
    if (fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment a fan: %u triangles around vertex 0 (bench/fan_mesh.c)\n"
                   "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face %u\nproperty list uchar int vertex_indices\nend_header\n", n, nv, n) < 0) return 1;
    for (k = 0; k < nv; ++k) {
        fan_vertex(k, n, span, tilt, p);
        put_f32(b, p[0]); put_f32(b + 4, p[1]); put_f32(b + 8, p[2]);
        if (fwrite(b, 1, 12, f) != 12) return 1;
    }
    b[0] = 3;
    for (k = 0; k < n; ++k) {
        put_u32(b + 1, 0); put_u32(b + 5, k + 1); put_u32(b + 9, k + 2);
        if (fwrite(b, 1, 13, f) != 13) return 1;
    }
    return 0;
}
static int write_obj(FILE *f, uint32_t n, double span, int tilt)
{
    uint32_t k, nv = n + 2;
    float p[3];
    if (fprintf(f, "# a fan: one polygon of %u corners around corner 1 (bench/fan_mesh.c)\n", nv) < 0) return 1;
    for (k = 0; k < nv; ++k) {
        fan_vertex(k, n, span, tilt, p);
        if (fprintf(f, "v %.9g %.9g %.9g\n", (double)p[0], (double)p[1], (double)p[2]) < 0) return 1;
    }
    if (fputs("f", f) < 0) return 1;
    for (k = 1; k <= nv; ++k) if (fprintf(f, " %u", k) < 0) return 1;
    return fputs("\n", f) < 0;
}
int main(int argc, char **argv)
{
    double span = 90.0;
    int obj = 0, tilt = 0, i = 1, bad;
    unsigned long n;
    char *end;
    FILE *f;
    for (; i < argc && argv[i][0] == '-' && argv[i][1] == '-'; ++i) {
        if (strcmp(argv[i], "--obj") == 0) obj = 1;
        else if (strcmp(argv[i], "--tilt") == 0) tilt = 1;
        else if (strcmp(argv[i], "--span") == 0 && i + 1 < argc) span = atof(argv[++i]);
        else break;
    }
    if (argc - i != 2 || !(span > 0.0 && span <= 360.0)) {
        fprintf(stderr, "usage: fan_mesh [--span DEG (0, 360]] [--tilt] [--obj] N OUT\n");
        return 2;
    }
    n = strtoul(argv[i], &end, 10);
    if (*end || n < 1 || n > 0xFFFFFFF0ul) { fprintf(stderr, "fan_mesh: N must be a count of triangles, 1 .. 4294967280\n"); return 2; }
    if (!(f = fopen(argv[i + 1], "wb"))) { perror(argv[i + 1]); return 1; }
    span *= 3.14159265358979323846 / 180.0;
    bad = obj ? write_obj(f, (uint32_t)n, span, tilt) : write_ply(f, (uint32_t)n, span, tilt);
    if (fclose(f) != 0) bad = 1;
    if (bad) { fprintf(stderr, "fan_mesh: cannot write %s\n", argv[i + 1]); return 1; }
    return 0;
}
