/* Compiled as C: proves sh_grid_runtime_c.h is a valid C header and the API is usable from C. */
#include "sh_grid_runtime_c.h"

int q3sh_test_c_sample(const unsigned char* bsp, size_t size, const float position[3], const float normal[3],
                       float rgb[3], char* error, size_t errorSize) {
    float coeffs[27];
    q3sh_grid* grid = q3sh_grid_load(bsp, size, error, errorSize);
    if (grid == NULL) return -1;
    q3sh_grid_sample(grid, position, coeffs);
    q3sh_eval_irradiance(coeffs, normal, rgb);
    {
        const int source = q3sh_grid_source(grid);
        q3sh_grid_free(grid);
        return source;
    }
}
