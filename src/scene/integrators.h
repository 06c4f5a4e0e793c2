/* integrators.h: the list of integrators, one line each, which everything that names them reads:
 * the scene's `integrator { method NAME }` (scene.h's enum integrator_kind and
 * mc_integrator_names, the parser's words), mcrt_options.integrator and --integrator (through
 * mcrt_names and src/integrator/integrators.c, which maps each line to its descriptor), --help,
 * and tests/docs.sh (through `mcrt --list integrator`).
 *
 * X(ID, name): ID gives the enum constant INTEGRATOR_<ID>; name is the word, and the descriptor
 * `const struct integrator mc_integrator_<name>` (integrator/integrator.h) is defined in a file
 * of src/integrator/. Adding an integrator is that file and one line here. The list lives in the
 * scene layer, below the integrators, because the scene language names them; it includes
 * nothing. The order is the order of --help and of the enum. */
#ifndef MCRT_SCENE_INTEGRATORS_H
#define MCRT_SCENE_INTEGRATORS_H

#define MC_INTEGRATORS(X) \
    X(PATH, path)         \
    X(DIRECT, direct)     \
    X(MIS, mis)           \
    X(BSDF, bsdf)         \
    X(LIGHT, light)       \
    X(SPPM, sppm)

#endif
