/* Render the volumetric cloudscape with the C library alone: generate the four textures, set up the camera and the
 * Preetham sky, render a frame on one thread and write it as a binary PPM.
 *
 *   cloudscape_ppm [width height [out.ppm]]      (default 320 x 180, cloudscape.ppm)
 *
 * The base texture is 64^3 here (the thesis' 128^3 takes ~2 s more to generate on one core). */
#include <stdio.h>
#include <stdlib.h>
#include <cclouds/cclouds.h>

static float *make(size_t n)
{
    float *p = (float *)malloc(n * sizeof *p);
    if (!p) fprintf(stderr, "out of memory\n");
    return p;
}

/* RGB (n texels x 3) -> RGBA (n x 4, A = 0); 2-channel -> RGBA likewise. */
static float *to_rgba(const float *src, size_t texels, int channels)
{
    float *dst = make(texels * 4u);
    size_t i;
    int c;
    if (!dst) return NULL;
    for (i = 0; i < texels; ++i)
        for (c = 0; c < 4; ++c) dst[i * 4u + (size_t)c] = c < channels ? src[i * (size_t)channels + (size_t)c] : 0.0f;
    return dst;
}

/* A size argument: an integer in [1, 8192], else 0. */
static int size_arg(const char *s)
{
    char *end;
    long v = strtol(s, &end, 10);
    return (end != s && *end == '\0' && v >= 1 && v <= 8192) ? (int)v : 0;
}

int main(int argc, char **argv)
{
    int width = argc > 2 ? size_arg(argv[1]) : 320, height = argc > 2 ? size_arg(argv[2]) : 180, x, y, ok = 1;
    int status = 1;
    const char *path = argc > 3 ? argv[3] : "cloudscape.ppm";
    ccl_base_shape_settings bs = ccl_texgen_base_shape_settings_default();
    ccl_detail_shape_settings ds = ccl_texgen_detail_shape_settings_default();
    ccl_curl_noise_settings cs = ccl_texgen_curl_noise_settings_default();
    ccl_weather_map_settings ws = ccl_texgen_weather_map_settings_default();
    ccl_cloudscape_params params;
    ccl_cloudscape_sky sky;
    ccl_cloud_textures tex;
    ccl_camera cam;
    ccl_vec3 eye = {0.0f, 0.3f, 0.0f}, target = {0.0f, 0.664f, -1.0f}, up = {0.0f, 1.0f, 0.0f};
    /* every buffer starts NULL, so the one exit below frees whatever was allocated on every path */
    float *base = NULL, *detail3 = NULL, *curl2 = NULL, *weather = NULL, *detail = NULL, *curl = NULL, *img = NULL,
          *base_mips = NULL, *detail_mips = NULL;
    size_t nb, nd, nc, nw, npx;
    FILE *f;

    if (width < 1 || height < 1) {
        fprintf(stderr, "usage: %s [width height [out.ppm]]   (width, height in [1, 8192])\n", argv[0]);
        return 2;
    }
    bs.size = 64;
    ws.size = 256;
    nb = (size_t)bs.size * (size_t)bs.size * (size_t)bs.size;
    nd = (size_t)ds.size * (size_t)ds.size * (size_t)ds.size;
    nc = (size_t)cs.size * (size_t)cs.size;
    nw = (size_t)ws.size * (size_t)ws.size;
    npx = (size_t)width * (size_t)height * 3u;
    base = make(nb * 4u);
    detail3 = make(nd * 3u);
    curl2 = make(nc * 2u);
    weather = make(nw * 4u);
    img = make(npx);
    if (!base || !detail3 || !curl2 || !weather || !img) goto done;
    if (ccl_texgen_base_shape(&bs, base, nb * 4u) || ccl_texgen_detail_shape(&ds, detail3, nd * 3u) ||
        ccl_texgen_curl_noise(&cs, curl2, nc * 2u) || ccl_texgen_weather_map(&ws, weather, nw * 4u)) {
        fprintf(stderr, "texture generation failed\n");
        goto done;
    }
    detail = to_rgba(detail3, nd, 3);
    curl = to_rgba(curl2, nc, 2);
    if (!detail || !curl) goto done;
    tex.base = base;
    tex.base_size = bs.size;
    tex.detail = detail;
    tex.detail_size = ds.size;
    tex.curl = curl;
    tex.curl_size = cs.size;
    tex.weather = weather;
    tex.weather_size = ws.size;
    /* the mip chains of the level of detail (params.lod) */
    base_mips = make(ccl_cloudscape_mip3_len(bs.size));
    detail_mips = make(ccl_cloudscape_mip3_len(ds.size));
    if (!base_mips || !detail_mips ||
        ccl_cloudscape_mip3(base, bs.size, base_mips, ccl_cloudscape_mip3_len(bs.size)) ||
        ccl_cloudscape_mip3(detail, ds.size, detail_mips, ccl_cloudscape_mip3_len(ds.size))) {
        fprintf(stderr, "mip generation failed\n");
        goto done;
    }
    tex.base_mips = base_mips;
    tex.detail_mips = detail_mips;

    ccl_cloudscape_params_default(&params);
    sky.kind = CCL_SKY_PREETHAM;
    {
        const ccl_vec3 s = ccl_sky_sun_direction(35.0f, 150.0f);
        sky.sun[0] = s.x;
        sky.sun[1] = s.y;
        sky.sun[2] = s.z;
    }
    if (ccl_sky_preetham_init(2.5f, 0.9599311f /* 90 - 35 degrees */, 0.05f, CCL_VARIANT_CORRECTED, &sky.preetham) ||
        ccl_camera_look_at(eye, target, up, 1.0471976f /* 60 degrees */, (float)width / (float)height, 0.01f,
                           1000.0f, &cam) ||
        ccl_cloudscape_render(&params, &tex, &sky, &cam, width, height, 0, img, npx)) {
        fprintf(stderr, "render failed: invalid parameters\n");
        goto done;
    }
    f = fopen(path, "wb");
    if (!f) {
        perror(path);
        goto done;
    }
    ok &= fprintf(f, "P6\n%d %d\n255\n", width, height) > 0;
    for (y = 0; y < height; ++y)
        for (x = 0; x < width * 3; ++x)
            ok &= fputc((int)(img[(size_t)y * (size_t)width * 3u + (size_t)x] * 255.0f + 0.5f), f) != EOF;
    ok &= fclose(f) == 0;
    if (!ok) {
        fprintf(stderr, "%s: write failed\n", path);
        goto done;
    }
    printf("wrote %s (%dx%d)\n", path, width, height);
    status = 0;
done:
    free(base);
    free(detail3);
    free(curl2);
    free(weather);
    free(detail);
    free(curl);
    free(img);
    free(base_mips);
    free(detail_mips);
    return status;
}
