/* What the test models of this folder share: the few FMI 3.0 types they need (self-contained, no FMI headers)
 * and one macro that writes a Get/Set pair of a numeric type from a table of value references. Every FMI 3.0
 * function a model does not define is a weak stub returning fmi3Error (fmi3_stubs.c). */
#ifndef FMI3_MODEL_H
#define FMI3_MODEL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef enum { OK = 0, WARNING = 1, DISCARD = 2, ERROR = 3 } Status;
typedef unsigned int VR;

/* fmi3Get<NAME> / fmi3Set<NAME> for C type T: CASES is a list of `case VR: p = <address>; n = <count>; break;`
 * (n defaults to 1; an array variable gives its element count). An unknown value reference is an error. */
#define ACCESS(T, NAME, MODEL, CASES)                                                                        \
    Status fmi3Get##NAME(void *c, const VR vr[], size_t nvr, T values[], size_t nValues) {                   \
        MODEL *m = (MODEL *)c; size_t k = 0;                                                                 \
        for (size_t i = 0; i < nvr; i++) {                                                                   \
            T *p = NULL; size_t n = 1;                                                                       \
            switch (vr[i]) { CASES default: return ERROR; }                                                  \
            for (size_t j = 0; j < n; j++) { if (k >= nValues) return ERROR; values[k++] = p[j]; }           \
        }                                                                                                    \
        return k == nValues ? OK : ERROR;                                                                    \
    }                                                                                                        \
    Status fmi3Set##NAME(void *c, const VR vr[], size_t nvr, const T values[], size_t nValues) {             \
        MODEL *m = (MODEL *)c; size_t k = 0;                                                                 \
        for (size_t i = 0; i < nvr; i++) {                                                                   \
            T *p = NULL; size_t n = 1;                                                                       \
            switch (vr[i]) { CASES default: return ERROR; }                                                  \
            for (size_t j = 0; j < n; j++) { if (k >= nValues) return ERROR; p[j] = values[k++]; }           \
        }                                                                                                    \
        m->changed = true;                                                                                   \
        return k == nValues ? OK : ERROR;                                                                    \
    }

const char *fmi3GetVersion(void) { return "3.0"; }

#endif
