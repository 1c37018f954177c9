/* pu_visibility.h: the shared plugin code is linked into every plugin .so; its
 * symbols are hidden so two plugins (or two versions of one plugin during a
 * hot plug) loaded into one manager each call their own copy. */
#ifndef PU_VISIBILITY_H
#define PU_VISIBILITY_H

#if defined(__GNUC__) || defined(__clang__)
#define PU_HIDDEN __attribute__((visibility("hidden")))
#else
#define PU_HIDDEN
#endif

#endif
