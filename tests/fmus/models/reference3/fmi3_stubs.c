/* Every FMI 3.0 function as a weak symbol returning fmi3Error: fmpy loads them all, and a test model (the
 * other .c files of this folder) defines, strongly, only those it implements. Linked into each model's binary
 * by tests/fmus/conftest.py. */

#define STUB(NAME) __attribute__((weak)) int NAME(void) { return 3; /* fmi3Error */ }

STUB(fmi3ActivateModelPartition) STUB(fmi3CompletedIntegratorStep) STUB(fmi3DeserializeFMUState) STUB(fmi3DoStep)
STUB(fmi3EnterConfigurationMode) STUB(fmi3EnterContinuousTimeMode) STUB(fmi3EnterEventMode)
STUB(fmi3EnterInitializationMode) STUB(fmi3EnterStepMode) STUB(fmi3EvaluateDiscreteStates)
STUB(fmi3ExitConfigurationMode) STUB(fmi3ExitInitializationMode) STUB(fmi3FreeFMUState)
STUB(fmi3GetAdjointDerivative) STUB(fmi3GetBinary) STUB(fmi3GetBoolean) STUB(fmi3GetClock)
STUB(fmi3GetContinuousStateDerivatives) STUB(fmi3GetContinuousStates) STUB(fmi3GetDirectionalDerivative)
STUB(fmi3GetEventIndicators) STUB(fmi3GetFMUState) STUB(fmi3GetFloat32) STUB(fmi3GetFloat64) STUB(fmi3GetInt16)
STUB(fmi3GetInt32) STUB(fmi3GetInt64) STUB(fmi3GetInt8) STUB(fmi3GetIntervalDecimal) STUB(fmi3GetIntervalFraction)
STUB(fmi3GetNominalsOfContinuousStates) STUB(fmi3GetNumberOfContinuousStates) STUB(fmi3GetNumberOfEventIndicators)
STUB(fmi3GetNumberOfVariableDependencies) STUB(fmi3GetOutputDerivatives) STUB(fmi3GetShiftDecimal)
STUB(fmi3GetShiftFraction) STUB(fmi3GetString) STUB(fmi3GetUInt16) STUB(fmi3GetUInt32) STUB(fmi3GetUInt64)
STUB(fmi3GetUInt8) STUB(fmi3GetVariableDependencies) STUB(fmi3InstantiateModelExchange)
STUB(fmi3InstantiateScheduledExecution) STUB(fmi3Reset) STUB(fmi3SerializeFMUState)
STUB(fmi3SerializedFMUStateSize) STUB(fmi3SetBinary) STUB(fmi3SetBoolean) STUB(fmi3SetClock)
STUB(fmi3SetContinuousStates) STUB(fmi3SetDebugLogging) STUB(fmi3SetFMUState) STUB(fmi3SetFloat32)
STUB(fmi3SetFloat64) STUB(fmi3SetInt16) STUB(fmi3SetInt32) STUB(fmi3SetInt64) STUB(fmi3SetInt8)
STUB(fmi3SetIntervalDecimal) STUB(fmi3SetIntervalFraction) STUB(fmi3SetShiftDecimal) STUB(fmi3SetShiftFraction)
STUB(fmi3SetString) STUB(fmi3SetTime) STUB(fmi3SetUInt16) STUB(fmi3SetUInt32) STUB(fmi3SetUInt64)
STUB(fmi3SetUInt8) STUB(fmi3Terminate) STUB(fmi3UpdateDiscreteStates)
