/* The smallest C program using cclouds: evaluate the Henyey-Greenstein phase function (vc-2.13). */
#include <stdio.h>
#include <cclouds/cclouds.h>

int main(void)
{
    int v = ccl_version(); /* MAJOR * 10000 + MINOR * 100 + PATCH */
    float p = ccl_phase_hg(1.0f, 0.8f); /* forward peak: (1 + g) / (4 pi (1 - g)^2) = 3.58099 sr^-1 */
    printf("cclouds %d.%d.%d: HG(cos=1, g=0.8) = %.5f\n", v / 10000, v / 100 % 100, v % 100, (double)p);
    return (p > 3.5809f && p < 3.5811f) ? 0 : 1;
}
