/* main.c: the mcrt command: parse options, load the scene, render with a progress bar, write the
 * image and optional JSON statistics. A thin client of the public API (mcrt.h) and nothing else. */
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli/args.h"
#include "cli/converge.h"
#include "cli/denoise.h"
#include "cli/diff.h"
#include "cli/merge.h"
#include "mcrt.h"

/* The help, in three parts around the lines that list the library's names (print_usage). */
static const char usage[] =
    "usage: mcrt [render] [options] SCENE\n"
    "       mcrt info SCENE\n"
    "       mcrt pov SCENE [-o FILE]   (export for POV-Ray; see mcrt pov --help)\n"
    "       mcrt mitsuba SCENE [-o FILE]   (export for Mitsuba 3; see mcrt mitsuba --help)\n"
    "       mcrt diff [options] TEST REF   (compare images; see mcrt diff --help)\n"
    "       mcrt converge [options] SCENE  (error against time; see mcrt converge --help)\n"
    "       mcrt merge A.exr B.exr ... -o OUT.exr  (merge render states; see mcrt merge --help)\n"
    "Render the scene file SCENE (see mcrt(5)) and write the image; or, with info, print the\n"
    "features the scene uses, the sample dimensions one path draws and the memory it needs.\n"
    "\n"
    "options:\n"
    "  -o FILE             the image to write; its suffix picks the format: .png (8-bit sRGB),\n"
    "                      .exr (32-bit float) or .pfm (32-bit float). Default: SCENE's name\n"
    "                      with .png (.pfm if built without PNG), in the current folder\n"
    "  --spp N             samples per pixel (default: the scene's)\n"
    "  --threads N         worker threads; 0 means one per core (default: 0)\n"
    "  --seed N            random seed, 0 to 2^64-1 (default: 0); the image depends only on\n"
    "                      the scene, the options and the seed, not on the number of threads\n"
    "  --integrator NAME   the estimator, one of (default: the scene's integrator method):\n";
/* After the integrators, one line each (print_usage). */
static const char usage_tail[] =
    "  --all-features      render with the general code path instead of the one built for the\n"
    "                      features the scene uses (the same image in expectation; slower)\n"
    "  --stats FILE        write statistics as JSON (size, spp, threads, seconds, rays, NaNs,\n"
    "                      estimated relative MSE, efficiency)\n";
static const char usage_after_aov[] =
    "                      (see mcrt(1)); layer NAME has channels NAME.R/G/B, and halves\n"
    "                      the layers A and B, the means of each half of a pixel's samples\n"
    "  --crop x0,y0,x1,y1  render only pixels x0 <= x < x1, y0 <= y < y1 (each as in the\n"
    "                      whole image with the same seed)\n"
    "  --time SECONDS      render passes of --spp samples until the time is spent\n"
    "  --target-error E    render passes of --spp samples until the estimated relative MSE\n"
    "                      is at most E; the progress bar shows the predicted time to it\n"
    "  --adaptive          after a uniform first pass, give each pixel samples in proportion\n"
    "                      to its estimated error; --spp is then the mean per pixel\n"
    "  --passes N          render N passes of --spp samples in all (with --resume's)\n"
    "  --first-pass K      start at pass K of the seed's passes, for renders that mcrt merge\n"
    "                      combines into the samples of one (machines sharing a render)\n"
    "  --state             keep the render's state in the EXR image (as --time and\n"
    "                      --target-error always do), for --resume and mcrt merge\n"
    "  --resume FILE.exr   go on from FILE's state: the image is bit-identical to one render\n"
    "                      of the same passes; refused for another scene, options or seed\n"
    "  --denoise           denoise the image (NFOR, from the two half buffers and the first\n"
    "                      non-specular surface's albedo, normal, depth and emission); an EXR\n"
    "                      also gets the raw image (layer raw) and the denoiser's inputs\n";
static const char usage_after_sampler[] =
    "  --list SET          print the names of a set, one a line (with a tab and a description\n"
    "                      where the set has them): integrator, sampler, aov, filter, shape,\n"
    "                      light, material, texture\n"
    "  --quiet             print nothing but errors\n"
    "  --help              print this help and exit\n"
    "  --version           print the version and the built-in image formats, and exit\n"
    "An option's value may also follow an equals sign, as in --spp=64.\n"
    "\n"
    "exit status:\n"
    "  0  success\n"
    "  1  failure: the image or statistics could not be written, out of memory\n"
    "  2  bad input: bad options, a missing or malformed scene, an unsupported image format\n"
    "  130  interrupted (Ctrl-C): the complete passes were written; a second Ctrl-C quits\n"
    "       at once and leaves the output alone\n";

/* --help: the usage, with the names the library's tables hold (mcrt_names, mcrt_describe). */
static int print_usage(void)
{
    const char *const *it = mcrt_names("integrator");
    char names[128];
    int i, width = 0;
    fputs(usage, stdout);
    for (i = 0; it[i]; i++)
        width = (int)strlen(it[i]) > width ? (int)strlen(it[i]) : width;
    for (i = 0; it[i]; i++)
        printf("                      %-*s  %s\n", width, it[i], mcrt_describe("integrator", it[i]));
    fputs(usage_tail, stdout);
    printf("  --aov LIST          extra layers in the EXR image, comma-separated, of: %s\n",
           mc_args_names("aov", ", ", ", ", names, sizeof names));
    fputs(usage_after_aov, stdout);
    printf("  --sampler NAME      %s (default: the scene's)\n",
           mc_args_names("sampler", ", ", " or ", names, sizeof names));
    fputs(usage_after_sampler, stdout);
    return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
}

/* --list SET: one of the library's tables, for scripts (tests/docs.sh). */
static int print_list(const char *set)
{
    const char *const *names = mcrt_names(set);
    int i;
    if (!names) {
        fprintf(stderr, "mcrt: --list: unknown set '%s'\n", set);
        return STATUS_USAGE;
    }
    for (i = 0; names[i]; i++) {
        const char *description = mcrt_describe(set, names[i]);
        printf(description ? "%s\t%s\n" : "%s\n", names[i], description);
    }
    return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
}

/* Image formats, for --version and for explaining a format this build lacks. */
static const struct {
    const char *suffix, *library, *package;
} formats[] = {
    {"png", "libpng", "libpng-dev"}, {"exr", "OpenEXR", "libopenexr-dev"}, {"pfm", NULL, NULL}};
#define NFORMATS (sizeof formats / sizeof formats[0])

static int print_version(void)
{
    size_t i;
    printf("mcrt %s\nimage formats:", mcrt_version());
    for (i = 0; i < NFORMATS; i++)
        if (mcrt_format_supported(formats[i].suffix))
            printf(" %s", formats[i].suffix);
    printf("\n");
    return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
}

/* The suffix of path's last component without the dot ("" if none). */
static const char *suffix_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash + 1 : path, '.');
    return dot ? dot + 1 : "";
}

/* Whether the image file can be written, known before spending time on rendering. */
static int check_output(const char *path)
{
    const char *suffix = suffix_of(path);
    size_t i;
    if (mcrt_format_supported(suffix))
        return 1;
    for (i = 0; i < NFORMATS; i++)
        if (formats[i].library && strcasecmp(suffix, formats[i].suffix) == 0) {
            fprintf(stderr, "mcrt: cannot write '%s': this mcrt was built without %s "
                            "(install %s and rebuild)\n",
                    path, formats[i].library, formats[i].package);
            return 0;
        }
    if (suffix[0])
        fprintf(stderr,
                "mcrt: cannot write '%s': unknown image format '.%s' (use .png, .exr or .pfm)\n",
                path, suffix);
    else
        fprintf(stderr, "mcrt: cannot write '%s': no image suffix (use .png, .exr or .pfm)\n",
                path);
    return 0;
}

/* Whether a file can be created at path: its folder exists and is writable. */
static int check_folder(const char *path)
{
    const char *slash = strrchr(path, '/');
    size_t len = slash ? (size_t)(slash - path) + 1 : 0; /* keep the slash: "/x" is in "/" */
    char *dir = malloc(len + 2);
    int ok;
    if (!dir)
        return 1; /* the write itself will report it */
    memcpy(dir, len ? path : ".", len ? len : 1);
    dir[len ? len : 1] = '\0';
    ok = access(dir, W_OK | X_OK) == 0;
    if (!ok)
        fprintf(stderr, "mcrt: cannot write '%s': %s\n", path, strerror(errno));
    free(dir);
    return ok;
}

/* SCENE's file name with its suffix replaced, in the current folder: scenes/box.mcrt -> box.png. */
static char *default_output(const char *scene, const char *ext)
{
    const char *base = strrchr(scene, '/'), *dot;
    size_t len;
    char *out;
    base = base ? base + 1 : scene;
    dot = strrchr(base, '.');
    len = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    out = malloc(len + strlen(ext) + 2);
    if (out)
        sprintf(out, "%.*s.%s", (int)len, base, ext);
    return out;
}

static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/* ---- progress bar ---- */

struct progress {
    double start, last_draw;
    int width; /* characters last drawn, to erase them */
};

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void format_time(char *buf, size_t size, double seconds)
{
    long s = (long)(seconds + 0.5);
    if (s >= 3600)
        snprintf(buf, size, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    else
        snprintf(buf, size, "%ld:%02ld", s / 60, s % 60);
}

/* The render's progress callback: called after tiles from worker threads, one call at a time,
 * so the state needs no lock. Redraws at most 10 times a second, plus once at the end. */
static int on_progress(void *user, double done)
{
    static const char bar[] = "##############################";
    struct progress *p = user;
    double t = now(), elapsed = t - p->start;
    char took[32], left[32];
    int filled = (int)(done * (sizeof bar - 1));
    if (done < 1.0 && t - p->last_draw < 0.1)
        return 0;
    p->last_draw = t;
    format_time(took, sizeof took, elapsed);
    if (done > 0.0)
        format_time(left, sizeof left, elapsed * (1.0 - done) / done);
    else
        snprintf(left, sizeof left, "?");
    p->width = fprintf(stderr, "\r[%-*.*s] %3d%%  %s elapsed, %s left ", (int)(sizeof bar - 1),
                       filled, bar, (int)(done * 100.0), took, left) - 1;
    fflush(stderr);
    return 0;
}

static void progress_clear(struct progress *p)
{
    if (p->width > 0)
        fprintf(stderr, "\r%*s\r", p->width, "");
}

/* ---- the render command ---- */

/* The options of mcrt-mpi's too (MC_RENDER_ARGS), then mcrt's own. */
enum { OPT_OUTPUT = RENDER_ARGS_END, OPT_STATS, OPT_QUIET, OPT_HELP, OPT_VERSION, OPT_AOV,
       OPT_ADAPTIVE, OPT_LIST, OPT_FIRST_PASS, OPT_RESUME, OPT_DENOISE, OPT_END };
static const struct arg_spec render_options[OPT_END + 1] = {
    MC_RENDER_ARGS(MC_RENDER_ARG_SPEC)
    [OPT_OUTPUT] = {NULL, 'o', 1},        [OPT_STATS] = {"stats", 0, 1},
    [OPT_QUIET] = {"quiet", 0, 0},        [OPT_HELP] = {"help", 0, 0},
    [OPT_VERSION] = {"version", 0, 0},    [OPT_AOV] = {"aov", 0, 1},
    [OPT_ADAPTIVE] = {"adaptive", 0, 0},  [OPT_LIST] = {"list", 0, 1},
    [OPT_FIRST_PASS] = {"first-pass", 0, 1}, [OPT_RESUME] = {"resume", 0, 1},
    [OPT_DENOISE] = {"denoise", 0, 0},
    [OPT_END] = {NULL, 0, 0}};

struct render_args {
    const char *scene, *output, *stats;
    int quiet;
    mcrt_options o; /* the render's, but for the progress callback */
};

/* Parse the command line into a; returns -1 to go on, or the exit status to stop with. */
static int parse_render_args(int argc, char **argv, struct render_args *a)
{
    struct arg_parser p;
    const char *v;
    int opt;
    memset(a, 0, sizeof *a);
    mcrt_options_init(&a->o);
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, render_options, &v)) != ARG_END) {
        if (opt >= 0 && opt < RENDER_ARGS_END) {
            if (!mc_args_render(opt, v, &a->o))
                return STATUS_USAGE;
            continue;
        }
        switch (opt) {
        case ARG_ERROR:
            return STATUS_USAGE;
        case ARG_OPERAND:
            if (a->scene) {
                fprintf(stderr, "mcrt: more than one scene given ('%s' and '%s')\n", a->scene, v);
                return STATUS_USAGE;
            }
            a->scene = v;
            break;
        case OPT_OUTPUT:
            a->output = v;
            break;
        case OPT_STATS:
            a->stats = v;
            break;
        case OPT_AOV:
            a->o.aovs = v;
            break;
        case OPT_ADAPTIVE:
            a->o.adaptive = 1;
            break;
        case OPT_DENOISE:
            a->o.denoise = 1;
            break;
        case OPT_FIRST_PASS:
            if (!mc_args_int("first-pass", v, 0, 2147483647, &a->o.first_pass))
                return STATUS_USAGE;
            break;
        case OPT_RESUME:
            a->o.resume = v;
            break;
        case OPT_QUIET:
            a->quiet = 1;
            break;
        case OPT_HELP:
            return print_usage();
        case OPT_LIST:
            return print_list(v);
        case OPT_VERSION:
            return print_version();
        }
    }
    if (!a->scene) {
        fprintf(stderr, "mcrt: no scene file given (see mcrt --help)\n");
        return STATUS_USAGE;
    }
    return -1;
}

/* ---- Ctrl-C ---- */

/* The first SIGINT cancels the running render (mcrt_render_cancel is safe in a signal handler),
 * whose complete passes are then written; the second quits at once, leaving the output alone. */
static volatile sig_atomic_t interrupts;
static mcrt_render *volatile running;

static void on_sigint(int sig)
{
    (void)sig;
    if (interrupts)
        _exit(130);
    interrupts = 1;
    if (running)
        mcrt_render_cancel(running);
}

static void sigint_catch(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
}

/* After a render stopped by Ctrl-C: write the complete passes, if any; exit status 130 (128 +
 * SIGINT, the shell's convention). */
static int interrupted(mcrt_render *r, const char *output)
{
    mcrt_stats st;
    mcrt_render_stats(r, &st, sizeof st);
    if (st.passes == 0) {
        fprintf(stderr, "mcrt: interrupted before a pass was complete; nothing written\n");
        return 130;
    }
    if (mcrt_render_save(r, output) != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", mcrt_render_error(r));
        return STATUS_FAIL;
    }
    fprintf(stderr, "mcrt: interrupted; wrote %s with the %d complete pass%s (%d spp)\n", output,
            st.passes, st.passes == 1 ? "" : "es", st.spp);
    return 130;
}

/* Load, render and write; the output paths have been checked. */
static int render(const struct render_args *a, const char *output)
{
    mcrt_scene *scene = mcrt_scene_new();
    mcrt_render *r = NULL;
    mcrt_options o;
    mcrt_stats st;
    struct progress prog;
    mcrt_status status;
    int code = STATUS_FAIL;
    char passes[96] = "", to_goal[64] = "";

    if (!scene) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    status = mcrt_scene_load_file(scene, a->scene);
    if (status != MCRT_OK) {
        fprintf(stderr, "%s\n", mcrt_scene_error(scene)); /* already "file:line:col: ..." */
        mcrt_scene_free(scene);
        return status == MCRT_ERR_NOMEM ? STATUS_FAIL : STATUS_USAGE;
    }
    if (!a->quiet)
        fputs(mcrt_scene_warnings(scene), stderr);
    o = a->o;
    if (!a->quiet && isatty(STDERR_FILENO)) {
        prog.start = now();
        prog.last_draw = 0.0;
        prog.width = 0;
        o.progress = on_progress;
        o.user = &prog;
    }
    r = mcrt_render_new(scene, &o);
    if (!r) {
        fprintf(stderr, "mcrt: out of memory\n");
        goto done;
    }
    running = r;
    sigint_catch();
    status = mcrt_render_run(r);
    running = NULL;
    if (o.progress)
        progress_clear(&prog);
    if (status == MCRT_ERR_CANCELLED && interrupts) {
        code = interrupted(r, output);
        goto done;
    }
    if (status != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", mcrt_render_error(r));
        /* MCRT_ERR_INVALID: options the library refused (e.g. more spp than it allows). */
        code = status == MCRT_ERR_INVALID ? STATUS_USAGE : STATUS_FAIL;
        goto done;
    }
    if (mcrt_render_save(r, output) != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", mcrt_render_error(r));
        goto done;
    }
    mcrt_render_stats(r, &st, sizeof st);
    if (a->stats && mcrt_render_save_stats(r, a->stats, a->scene, output) != MCRT_OK) {
        fprintf(stderr, "mcrt: %s\n", mcrt_render_error(r));
        goto done;
    }
    /* Progressive renders say how many passes ran; adaptive ones how far the pixels' samples
     * spread (spp is then their mean). */
    if (o.time_budget > 0.0 || o.target_error > 0.0 || o.passes || o.resume || st.adaptive)
        snprintf(passes, sizeof passes, ", %d pass%s%s", st.passes, st.passes == 1 ? "" : "es",
                 st.adaptive ? ", adaptive" : "");
    if (st.adaptive)
        snprintf(passes + strlen(passes), sizeof passes - strlen(passes), " (%d to %d spp)",
                 st.spp_min, st.spp_max);
    /* A denoised image's estimated error beside the raw one's; the time to a lower error is
     * predicted for raw renders only (the denoiser's error falls at its own rate). */
    if (o.denoise)
        snprintf(to_goal, sizeof to_goal, " +- %.2g (raw %.3g, denoised in %.2f s)",
                 st.est_relmse_sd, st.est_relmse_raw, st.denoise_seconds);
    else if (st.est_relmse > 0.0) { /* the time to the next power of ten below the error */
        double goal = pow(10.0, floor(log10(st.est_relmse)));
        char took[32];
        goal = goal < st.est_relmse ? goal : goal / 10.0;
        double t = mcrt_seconds_to_relmse(&st, goal);
        if (t < 60.0)
            snprintf(took, sizeof took, "%.2g s", t);
        else
            format_time(took, sizeof took, t);
        snprintf(to_goal, sizeof to_goal, " (%.0e in %s)", goal, took);
    }
    if (!a->quiet)
        fprintf(stderr,
                "%s: %dx%d, %d spp, %d thread%s, %.*f s, %.2f Mrays/s, %" PRIu64 " NaN samples, "
                "est. relMSE %.3g%s, efficiency %.3g%s\n",
                output, st.width, st.height, st.spp, st.threads, st.threads == 1 ? "" : "s",
                st.seconds < 10.0 ? 2 : 1, st.seconds,
                st.seconds > 0.0 ? (double)st.rays / st.seconds * 1e-6 : 0.0, st.nan_count,
                st.est_relmse, to_goal, st.efficiency, passes);
    code = STATUS_OK;
done:
    mcrt_render_free(r);
    mcrt_scene_free(scene);
    return code;
}

static int cmd_render(int argc, char **argv)
{
    struct render_args a;
    char *owned = NULL;
    const char *output;
    int code = parse_render_args(argc, argv, &a);
    if (code >= 0)
        return code;
    output = a.output ? a.output : (owned = default_output(a.scene, mcrt_format_supported("png") ? "png" : "pfm"));
    if (!output) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    /* Everything that can be known to fail is checked before the render, not after it. */
    if (!check_output(output) || !check_folder(output) || (a.stats && !check_folder(a.stats)))
        code = STATUS_USAGE;
    else if ((a.o.aovs || a.o.save_state) && strcasecmp(suffix_of(output), "exr") != 0) {
        fprintf(stderr, "mcrt: --%s needs an EXR image, not '%s'\n", a.o.aovs ? "aov" : "state",
                output);
        code = STATUS_USAGE;
    }
    else if (same_file(a.scene, output) || (a.stats && same_file(a.scene, a.stats))) {
        fprintf(stderr, "mcrt: refusing to overwrite the scene file '%s'\n", a.scene);
        code = STATUS_USAGE;
    } else
        code = render(&a, output);
    free(owned);
    return code;
}

/* ---- the info command ---- */

static int cmd_info(int argc, char **argv)
{
    mcrt_scene *scene;
    mcrt_status status;
    int code;
    if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return print_usage();
    if (argc != 2) {
        fprintf(stderr, "mcrt: usage: mcrt info SCENE\n");
        return STATUS_USAGE;
    }
    if (!(scene = mcrt_scene_new())) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    status = mcrt_scene_load_file(scene, argv[1]);
    if (status != MCRT_OK) {
        fprintf(stderr, "%s\n", mcrt_scene_error(scene));
        code = status == MCRT_ERR_NOMEM ? STATUS_FAIL : STATUS_USAGE;
    } else {
        fputs(mcrt_scene_warnings(scene), stderr);
        fputs(mcrt_scene_info(scene), stdout);
        code = fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
    }
    mcrt_scene_free(scene);
    return code;
}

/* ---- the exporters: pov and mitsuba ---- */

static const char pov_usage[] =
    "usage: mcrt pov SCENE [-o FILE]\n"
    "Write SCENE as a POV-Ray 3.7 scene with the physical mapping of mcrt(1), for an independent\n"
    "reference render; its second line is a comment with the pinned povray flags.\n"
    "\n"
    "options:\n"
    "  -o FILE   the POV-Ray file to write (default: SCENE's name with .pov, in the current\n"
    "            folder)\n"
    "  --help    print this help and exit\n"
    "\n"
    "exit status: 0 success; 1 the file could not be written; 2 bad input, or a scene that uses\n"
    "something POV-Ray cannot reproduce faithfully (the message names it)\n";

static const char mitsuba_usage[] =
    "usage: mcrt mitsuba SCENE [-o FILE]\n"
    "Write SCENE as a Mitsuba 3 XML scene (variant scalar_rgb) with the mapping of mcrt(1), its\n"
    "triangles as OBJ files beside it (FILE without .xml, then -mesh0.obj, ...).\n"
    "\n"
    "options:\n"
    "  -o FILE   the XML file to write (default: SCENE's name with .xml, in the current folder)\n"
    "  --help    print this help and exit\n"
    "\n"
    "exit status: 0 success; 1 a file could not be written; 2 bad input, or a scene that uses\n"
    "something Mitsuba cannot reproduce (the message names it, at its place in SCENE)\n";

/* An exporter as a command: `mcrt NAME SCENE [-o FILE]`. */
struct exporter {
    const char *name, *usage, *suffix;
    mcrt_status (*save)(mcrt_scene *s, const char *path);
};

enum { EXPORT_OUTPUT, EXPORT_HELP, EXPORT_END };
static const struct arg_spec export_options[EXPORT_END + 1] = {
    [EXPORT_OUTPUT] = {NULL, 'o', 1}, [EXPORT_HELP] = {"help", 0, 0}, [EXPORT_END] = {NULL, 0, 0}};

static int run_export(int argc, char **argv, const struct exporter *e)
{
    struct arg_parser p;
    const char *v, *scene_path = NULL, *output = NULL;
    char *owned = NULL;
    mcrt_scene *scene;
    mcrt_status status;
    int opt, code;
    mc_args_init(&p, argc, argv);
    while ((opt = mc_args_next(&p, export_options, &v)) != ARG_END) {
        if (opt == ARG_ERROR)
            return STATUS_USAGE;
        if (opt == EXPORT_HELP) {
            fputs(e->usage, stdout);
            return fflush(stdout) == 0 ? STATUS_OK : STATUS_FAIL;
        }
        if (opt == EXPORT_OUTPUT)
            output = v;
        else if (scene_path) {
            fprintf(stderr, "mcrt: more than one scene given ('%s' and '%s')\n", scene_path, v);
            return STATUS_USAGE;
        } else
            scene_path = v;
    }
    if (!scene_path) {
        fprintf(stderr, "mcrt: no scene file given (see mcrt %s --help)\n", e->name);
        return STATUS_USAGE;
    }
    if (!output && !(output = owned = default_output(scene_path, e->suffix))) {
        fprintf(stderr, "mcrt: out of memory\n");
        return STATUS_FAIL;
    }
    if (same_file(scene_path, output)) {
        fprintf(stderr, "mcrt: refusing to overwrite the scene file '%s'\n", scene_path);
        free(owned);
        return STATUS_USAGE;
    }
    if (!(scene = mcrt_scene_new())) {
        fprintf(stderr, "mcrt: out of memory\n");
        free(owned);
        return STATUS_FAIL;
    }
    status = mcrt_scene_load_file(scene, scene_path);
    if (status != MCRT_OK) { /* a missing or malformed scene is bad input */
        fprintf(stderr, "%s\n", mcrt_scene_error(scene)); /* already "file:line:col: ..." */
        code = status == MCRT_ERR_NOMEM ? STATUS_FAIL : STATUS_USAGE;
    } else {
        fputs(mcrt_scene_warnings(scene), stderr);
        code = STATUS_OK;
        if ((status = e->save(scene, output)) == MCRT_ERR_UNSUPPORTED) {
            fprintf(stderr, "%s\n", mcrt_scene_error(scene)); /* "file[:line:col]: cannot export" */
            code = STATUS_USAGE;
        } else if (status != MCRT_OK) {
            fprintf(stderr, "mcrt: %s\n", mcrt_scene_error(scene));
            code = status == MCRT_ERR_NOMEM || status == MCRT_ERR_IO ? STATUS_FAIL : STATUS_USAGE;
        }
    }
    mcrt_scene_free(scene);
    free(owned);
    return code;
}

static int cmd_pov(int argc, char **argv)
{
    static const struct exporter e = {"pov", pov_usage, "pov", mcrt_scene_export_pov};
    return run_export(argc, argv, &e);
}

static int cmd_mitsuba(int argc, char **argv)
{
    static const struct exporter e = {"mitsuba", mitsuba_usage, "xml", mcrt_scene_export_mitsuba};
    return run_export(argc, argv, &e);
}

/* ---- commands ---- */

/* Commands by name (`mcrt NAME ...`); without one, mcrt renders. Each gets argv from its name. */
static const struct command {
    const char *name;
    int (*run)(int argc, char **argv);
} commands[] = {{"render", cmd_render}, {"info", cmd_info}, {"pov", cmd_pov}, {"mitsuba", cmd_mitsuba}, {"diff", mc_cli_diff}, {"converge", mc_cli_converge}, {"merge", mc_cli_merge},
                {"denoise", mc_cli_denoise}};

int main(int argc, char **argv)
{
    size_t i;
    for (i = 0; argc > 1 && i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(argv[1], commands[i].name) == 0)
            return commands[i].run(argc - 1, argv + 1);
    return cmd_render(argc, argv);
}
