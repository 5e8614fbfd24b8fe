/* fan.h - the vertices of a "fan": N long thin triangles that all share vertex 0, the mesh
   that defeats a BVH of axis-aligned boxes (each triangle's box reaches from the shared
   vertex to the far arc, so near that vertex every box overlaps every other). Used by
   bench/fan_mesh.c (which writes it as a file) and bench/bench.c (which builds it).

   Vertex 0 is the origin; vertices 1 .. N + 1 lie on a far arc of radius 1 around the z
   axis, from angle 0 to span (radians), in the plane z = 0, or with tilt in the plane
   z = (x + y) / 2, tilted against every axis (its boxes are then boxes, not rectangles, but
   rounding the vertices to float makes the slivers' normals scatter); triangle i is
   (0, i + 1, i + 2).                                                                     */
#ifndef BENCH_FAN_H
#define BENCH_FAN_H
#include <math.h>
#include <stdint.h>

static void fan_vertex(uint32_t k, uint32_t n, double span, int tilt, float p[3])
{
    double a = k == 0 ? 0.0 : span * (double)(k - 1) / (double)n;
    double x = k == 0 ? 0.0 : cos(a), y = k == 0 ? 0.0 : sin(a);
    p[0] = (float)x;
    p[1] = (float)y;
    p[2] = tilt ? (float)(0.5 * (x + y)) : 0.0f;
}
#endif
