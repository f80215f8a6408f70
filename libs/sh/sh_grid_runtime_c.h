/* C interface of the engine-side SH light grid runtime (sh_grid_runtime.h). No function throws
 * or aborts: failures return NULL / zeros and a one-line message. Coefficients are 27 floats,
 * coefficient-major (coeffs[3*i + channel]), the layout of the lump. */
#ifndef Q3SH_GRID_RUNTIME_C_H
#define Q3SH_GRID_RUNTIME_C_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct q3sh_grid q3sh_grid;

enum {
    Q3SH_SOURCE_NONE = 0,
    Q3SH_SOURCE_LUMP18 = 1, /* lump 18 of an IBSP v47 file */
    Q3SH_SOURCE_BSPX = 2,   /* BSPX lump "LIGHTGRID_SH" */
    Q3SH_SOURCE_LEGACY = 3  /* converted from the legacy grid, lump 15 */
};

/* Loads the grid from a BSP image in memory (copied; `bsp` may be freed afterwards). On failure
 * returns NULL and, when errorSize > 0, writes a NUL-terminated one-line message to `error`. */
q3sh_grid* q3sh_grid_load(const unsigned char* bsp, size_t size, char* error, size_t errorSize);
void q3sh_grid_free(q3sh_grid* grid);

int q3sh_grid_source(const q3sh_grid* grid);
/* Grid placement: point (x,y,z) sits at mins + (x,y,z)*cellSize. */
void q3sh_grid_info(const q3sh_grid* grid, float mins[3], float cellSize[3], int bounds[3]);

/* Trilinear sample at a world position, clamped to the grid border. */
void q3sh_grid_sample(const q3sh_grid* grid, const float position[3], float coeffs[27]);

/* max(0, irradiance) for a unit normal. */
void q3sh_eval_irradiance(const float coeffs[27], const float normal[3], float rgb[3]);
/* Six colours: irradiance towards +X, -X, +Y, -Y, +Z, -Z (faces[3*face + channel]). */
void q3sh_ambient_cube(const float coeffs[27], float faces[18]);
/* Legacy-grid style lighting: ambient + directed * max(0, n.direction). */
void q3sh_legacy_lighting(const float coeffs[27], float direction[3], float directed[3], float ambient[3]);

#ifdef __cplusplus
}
#endif

#endif
