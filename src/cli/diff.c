/* diff.c: the `mcrt diff` command: compare an image with a reference through mcrt_diff (mcrt.h),
 * print the error statistics and the z-test's verdict, and turn limits into an exit status. */
#include "cli/diff.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/args.h"
#include "mcrt.h"

static const char usage[] =
    "usage: mcrt diff [options] TEST REF\n"
    "Compare the image TEST with the reference REF (PNG, EXR or PFM of the same size): MSE,\n"
    "relative MSE (mean of (t-r)^2/(r^2+0.01)), PSNR (peak 1), largest error and bias, over the\n"
    "whole image and a crop window.\n"
    "\n"
    "options:\n"
    "  --crop x0,y0,x1,y1  also report the window x0 <= x < x1, y0 <= y < y1; limits and the\n"
    "                      z-test then apply to it\n"
    "  --layer NAME        compare the EXR layer NAME (channels NAME.R, .G, .B)\n"
    "  --max-relmse X      fail when the relative MSE exceeds X\n"
    "  --max-bias B        fail when the mean of TEST - REF exceeds B in magnitude\n"
    "  --variance FILE     z-test: FILE holds the variance of TEST's pixel means (its variance\n"
    "                      layer, as `mcrt --aov variance` writes, or its image)\n"
    "  --floor F           z-test: standard deviation added in quadrature, for REF's own error\n"
    "                      (default: 0)\n"
    "  --alpha A           z-test: chance that a correct image fails, Sidak-corrected over all\n"
    "                      pixels and channels (default: 0.01); 99.75% of pixels must agree.\n"
    "                      On failure a false-colour picture of z is written to TEST.z.png\n"
    "  --quiet             print nothing but errors\n"
    "\n"
    "exit status: 0 pass, 1 a limit or the z-test failed, 2 bad input\n";

enum { OPT_CROP, OPT_LAYER, OPT_MAX_RELMSE, OPT_MAX_BIAS, OPT_VARIANCE, OPT_FLOOR, OPT_ALPHA,
       OPT_QUIET, OPT_HELP, OPT_END };
static const struct arg_spec options[OPT_END + 1] = {
    [OPT_CROP] = {"crop", 0, 1},         [OPT_LAYER] = {"layer", 0, 1},
    [OPT_MAX_RELMSE] = {"max-relmse", 0, 1}, [OPT_MAX_BIAS] = {"max-bias", 0, 1},
    [OPT_VARIANCE] = {"variance", 0, 1}, [OPT_FLOOR] = {"floor", 0, 1},
    [OPT_ALPHA] = {"alpha", 0, 1},       [OPT_QUIET] = {"quiet", 0, 0},
    [OPT_HELP] = {"help", 'h', 0},       [OPT_END] = {NULL, 0, 0}};

/* TEST's path with its suffix replaced by ".z.png": out/a.exr -> out/a.z.png. */
static char *z_image_path(const char *test)
{
    const char *slash = strrchr(test, '/');
    const char *dot = strrchr(slash ? slash + 1 : test, '.');
    size_t len = dot ? (size_t)(dot - test) : strlen(test);
    char *out = malloc(len + 7);
    if (out)
        sprintf(out, "%.*s.z.png", (int)len, test);
    return out;
}

static void print_stats(const char *what, const mcrt_diff_stats *s)
{
    printf("%s: %zu pixels, MSE %.4g, relMSE %.4g, PSNR %.2f dB, max error %.4g, "
           "bias %.4g (R %.4g, G %.4g, B %.4g)\n",
           what, s->pixels, s->mse, s->relmse, s->psnr, s->max_abs, s->bias, s->bias_r, s->bias_g,
           s->bias_b);
}

int mc_cli_diff(int argc, char **argv)
{
    struct arg_parser p;
    mcrt_diff_options o;
    mcrt_diff_result r;
    const char *v, *files[2] = {NULL, NULL};
    double max_relmse = -1.0, max_bias = -1.0;
    int opt, nfiles = 0, quiet = 0, code = STATUS_OK, crop[4];
    char *zpath = NULL, error[512];

    mcrt_diff_options_init(&o);
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, options, &v)) != ARG_END) {
        int ok = 1;
        switch (opt) {
        case ARG_ERROR: return STATUS_USAGE;
        case ARG_OPERAND:
            if (nfiles == 2) {
                fprintf(stderr, "mcrt: diff takes two images, TEST and REF; '%s' is a third\n", v);
                return STATUS_USAGE;
            }
            files[nfiles++] = v;
            break;
        case OPT_CROP:
            if ((ok = mc_args_window("crop", v, crop))) {
                o.crop_x0 = crop[0];
                o.crop_y0 = crop[1];
                o.crop_x1 = crop[2];
                o.crop_y1 = crop[3];
            }
            break;
        case OPT_LAYER: o.layer = v; break;
        case OPT_MAX_RELMSE: ok = mc_args_real("max-relmse", v, 0, 0, &max_relmse); break;
        case OPT_MAX_BIAS: ok = mc_args_real("max-bias", v, 0, 0, &max_bias); break;
        case OPT_VARIANCE: o.variance = v; break;
        case OPT_FLOOR: ok = mc_args_real("floor", v, 0, 0, &o.floor); break;
        case OPT_ALPHA: ok = mc_args_real("alpha", v, 1, 1, &o.alpha); break;
        case OPT_QUIET: quiet = 1; break;
        case OPT_HELP:
            fputs(usage, stdout);
            return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
        }
        if (!ok)
            return STATUS_USAGE;
    }
    if (nfiles != 2) {
        fprintf(stderr, "mcrt: usage: mcrt diff [options] TEST REF (see mcrt diff --help)\n");
        return STATUS_USAGE;
    }
    if (o.variance && !(o.z_image = zpath = z_image_path(files[0]))) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    if (mcrt_diff(files[0], files[1], &o, &r, sizeof r, error, sizeof error) != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", error);
        free(zpath);
        /* Images that cannot be read or compared are bad input; a z image that cannot be
         * written is a failure. */
        return r.width == 0 || !r.ztest ? STATUS_USAGE : STATUS_FAIL;
    }
    if (!quiet) {
        print_stats("whole image", &r.whole);
        if (o.crop_x1)
            print_stats("crop", &r.crop);
    }
    if (max_relmse >= 0.0 && !(r.crop.relmse <= max_relmse)) {
        fprintf(stderr, "mcrt: relative MSE %.4g exceeds --max-relmse %g\n", r.crop.relmse,
                max_relmse);
        code = STATUS_FAIL;
    }
    if (max_bias >= 0.0 && !(fabs(r.crop.bias) <= max_bias)) {
        fprintf(stderr, "mcrt: bias %.4g exceeds --max-bias %g in magnitude\n", r.crop.bias,
                max_bias);
        code = STATUS_FAIL;
    }
    if (r.ztest) {
        if (!quiet)
            printf("z-test: %.4f%% of %zu pixels agree (%zu do not), alpha %g (Sidak: %.3g per "
                   "channel, |z| < %.3f), largest z %.3g: %s\n",
                   100.0 * r.agree, r.crop.pixels, r.rejected, o.alpha > 0.0 ? o.alpha : 0.01,
                   r.alpha_test, r.z_crit, r.max_z, r.ztest_pass ? "pass" : "FAIL");
        if (!r.ztest_pass) {
            fprintf(stderr, "mcrt: z-test failed: %.4f%% of pixels agree, 99.75%% needed; z image "
                            "in %s\n", 100.0 * r.agree, zpath);
            code = STATUS_FAIL;
        }
    }
    free(zpath);
    if (fflush(stdout) != 0)
        return STATUS_FAIL;
    return code;
}
