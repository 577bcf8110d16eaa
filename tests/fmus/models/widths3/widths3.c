/* An FMI 3.0 co-simulation test FMU in C for the types pythonfmu3 cannot declare: Float32 (scalar and array),
 * Int8, UInt8, Int16, UInt16, UInt32, and a Binary output; with a state x' = -x whose start value can be set,
 * a parameter k with a declared range, and a terminate request at the end of the step that reaches t_stop.
 * Built by tests/fmus/conftest.py with the system's C compiler. Self-contained: it declares the few FMI 3.0
 * types it needs; every FMI 3.0 function it does not implement returns fmi3Error (fmpy loads them all). */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

typedef enum { OK = 0, WARNING = 1, DISCARD = 2, ERROR = 3 } Status;
typedef unsigned int VR;

typedef struct {
    double t_stop, x;
    float f32_in, f32, f32a[2];
    int8_t i8_in, i8, k;
    uint8_t u8_in, u8;
    int16_t i16_in, i16;
    uint16_t u16_in, u16;
    uint32_t u32_in, u32;
    uint8_t blob[2];
} Model;

static void outputs(Model *m) {
    m->f32 = 1.5f * m->f32_in + (float)m->x;
    m->f32a[0] = m->f32;
    m->f32a[1] = -m->f32;
    m->i8 = (int8_t)(m->i8_in - m->k);
    m->u8 = (uint8_t)(m->u8_in + 1);
    m->i16 = (int16_t)(-m->i16_in);
    m->u16 = (uint16_t)(m->u16_in * 2);
    m->u32 = m->u32_in + 4000000000u;
}

const char *fmi3GetVersion(void) { return "3.0"; }

void *fmi3InstantiateCoSimulation(const char *name, const char *token, const char *resources, bool visible,
                                  bool loggingOn, bool eventModeUsed, bool earlyReturnAllowed,
                                  const VR required[], size_t nRequired, void *env, void *log, void *update) {
    Model *m = calloc(1, sizeof(Model));
    if (!m) return NULL;
    m->t_stop = 10.0;
    m->x = 1.0;
    m->k = 3;
    m->blob[0] = 0x0b;
    outputs(m);
    return m;
}

void fmi3FreeInstance(void *c) { free(c); }
Status fmi3SetDebugLogging(void *c, bool on, size_t n, const char *const cats[]) { return OK; }
Status fmi3EnterInitializationMode(void *c, bool tolDefined, double tol, double start, bool stopDefined,
                                   double stop) { return OK; }
Status fmi3ExitInitializationMode(void *c) { outputs((Model *)c); return OK; }
Status fmi3Terminate(void *c) { return OK; }
Status fmi3Reset(void *c) { return OK; }

Status fmi3DoStep(void *c, double t, double h, bool noSetPrior, bool *eventNeeded, bool *terminate,
                  bool *earlyReturn, double *lastSuccessfulTime) {
    Model *m = (Model *)c;
    m->x += h * (-m->x);
    outputs(m);
    *eventNeeded = false;
    *earlyReturn = false;
    *terminate = t + h >= m->t_stop - 1e-9;
    *lastSuccessfulTime = t + h;
    return OK;
}

/* one Get/Set pair per type: scalars by value reference, the Float32 array (vr 15) as two values */
#define ACCESS(T, NAME, CASES)                                                                               \
    Status fmi3Get##NAME(void *c, const VR vr[], size_t nvr, T values[], size_t nValues) {                   \
        Model *m = (Model *)c; size_t k = 0;                                                                 \
        for (size_t i = 0; i < nvr; i++) { T *p = NULL; size_t n = 1; switch (vr[i]) { CASES default: return ERROR; } \
            for (size_t j = 0; j < n; j++) values[k++] = p[j]; }                                             \
        return k == nValues ? OK : ERROR; }                                                                  \
    Status fmi3Set##NAME(void *c, const VR vr[], size_t nvr, const T values[], size_t nValues) {             \
        Model *m = (Model *)c; size_t k = 0;                                                                 \
        for (size_t i = 0; i < nvr; i++) { T *p = NULL; size_t n = 1; switch (vr[i]) { CASES default: return ERROR; } \
            for (size_t j = 0; j < n; j++) p[j] = values[k++]; }                                             \
        return k == nValues ? OK : ERROR; }

ACCESS(double, Float64, case 1: p = &m->t_stop; break; case 8: p = &m->x; break;)
ACCESS(float, Float32, case 2: p = &m->f32_in; break; case 9: p = &m->f32; break; case 15: p = m->f32a; n = 2; break;)
ACCESS(int8_t, Int8, case 3: p = &m->i8_in; break; case 10: p = &m->i8; break; case 17: p = &m->k; break;)
ACCESS(uint8_t, UInt8, case 4: p = &m->u8_in; break; case 11: p = &m->u8; break;)
ACCESS(int16_t, Int16, case 5: p = &m->i16_in; break; case 12: p = &m->i16; break;)
ACCESS(uint16_t, UInt16, case 6: p = &m->u16_in; break; case 13: p = &m->u16; break;)
ACCESS(uint32_t, UInt32, case 7: p = &m->u32_in; break; case 14: p = &m->u32; break;)

Status fmi3GetBinary(void *c, const VR vr[], size_t nvr, size_t sizes[], const uint8_t *values[], size_t nValues) {
    Model *m = (Model *)c;
    for (size_t i = 0; i < nvr; i++) {
        if (vr[i] != 16) return ERROR;
        sizes[i] = 1;
        values[i] = m->blob;
    }
    return OK;
}

#define STUB(NAME) Status NAME(void) { return ERROR; }
STUB(fmi3ActivateModelPartition) STUB(fmi3CompletedIntegratorStep) STUB(fmi3DeserializeFMUState)
STUB(fmi3EnterConfigurationMode) STUB(fmi3EnterContinuousTimeMode) STUB(fmi3EnterEventMode)
STUB(fmi3EnterStepMode) STUB(fmi3EvaluateDiscreteStates) STUB(fmi3ExitConfigurationMode)
STUB(fmi3FreeFMUState) STUB(fmi3GetAdjointDerivative) STUB(fmi3GetBoolean) STUB(fmi3GetClock)
STUB(fmi3GetContinuousStateDerivatives) STUB(fmi3GetContinuousStates) STUB(fmi3GetDirectionalDerivative)
STUB(fmi3GetEventIndicators) STUB(fmi3GetFMUState) STUB(fmi3GetInt32) STUB(fmi3GetInt64)
STUB(fmi3GetIntervalDecimal) STUB(fmi3GetIntervalFraction) STUB(fmi3GetNominalsOfContinuousStates)
STUB(fmi3GetNumberOfContinuousStates) STUB(fmi3GetNumberOfEventIndicators) STUB(fmi3GetNumberOfVariableDependencies)
STUB(fmi3GetOutputDerivatives) STUB(fmi3GetShiftDecimal) STUB(fmi3GetShiftFraction) STUB(fmi3GetString)
STUB(fmi3GetUInt64) STUB(fmi3GetVariableDependencies) STUB(fmi3InstantiateModelExchange)
STUB(fmi3InstantiateScheduledExecution) STUB(fmi3SerializeFMUState) STUB(fmi3SerializedFMUStateSize)
STUB(fmi3SetBinary) STUB(fmi3SetBoolean) STUB(fmi3SetClock) STUB(fmi3SetContinuousStates) STUB(fmi3SetFMUState)
STUB(fmi3SetInt32) STUB(fmi3SetInt64) STUB(fmi3SetIntervalDecimal) STUB(fmi3SetIntervalFraction)
STUB(fmi3SetShiftDecimal) STUB(fmi3SetShiftFraction) STUB(fmi3SetString) STUB(fmi3SetTime) STUB(fmi3SetUInt64)
STUB(fmi3UpdateDiscreteStates)
