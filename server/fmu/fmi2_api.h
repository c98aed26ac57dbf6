/*
 * The FMI 2.0 C API as netmc uses it: the fmi2 platform types, the callback functions an
 * importer hands to fmi2Instantiate, and the types of the co-simulation functions netmc calls.
 * Declared here from the definitions of the FMI 2.0.x standard (section 2.1, "Application
 * Programming Interface", and section 4, "FMI for Co-Simulation"); C and C++, so the test FMUs of
 * tests/fmu are built against the same declarations netmc loads them with.
 *
 * The function types follow the standard's "fmi2XxxTYPE" naming: an FMU binary exports each as a
 * plain C symbol "fmi2Xxx" (FMI 2.0, 2.1.1: no model-identifier prefix in a shared object).
 */
#ifndef NETMC_PLANT_FMU_FMI2_API_H
#define NETMC_PLANT_FMU_FMI2_API_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* FMI 2.0, 2.1.2: platform dependent types (the "default" platform of fmi2GetTypesPlatform). */
typedef void* fmi2Component;            /* an FMU instance, opaque to the importer */
typedef void* fmi2ComponentEnvironment; /* the importer's pointer handed back to the callbacks */
typedef void* fmi2FMUstate;             /* a saved FMU state, opaque to the importer */
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char* fmi2String;
typedef char fmi2Byte;

#define fmi2True 1
#define fmi2False 0

/* FMI 2.0, 2.1.3: status returned by the functions, in increasing severity (fmi2Pending only
 * for an asynchronous fmi2DoStep). */
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;

/* FMI 2.0, 2.1.5: the kind of instance fmi2Instantiate makes. */
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;

/* FMI 2.0, 2.1.5: the importer's callbacks. The logger's message is a printf format for the
 * trailing arguments; allocateMemory has calloc's semantics (zeroed memory). */
typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment componentEnvironment, fmi2String instanceName,
                                   fmi2Status status, fmi2String category, fmi2String message, ...);
typedef void* (*fmi2CallbackAllocateMemory)(size_t nobj, size_t size);
typedef void (*fmi2CallbackFreeMemory)(void* obj);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment componentEnvironment, fmi2Status status);

typedef struct {
  fmi2CallbackLogger logger;
  fmi2CallbackAllocateMemory allocateMemory;
  fmi2CallbackFreeMemory freeMemory;
  fmi2StepFinished stepFinished; /* may be NULL: only for an asynchronous fmi2DoStep */
  fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

/* FMI 2.0, 2.1.4: inquire the platform and the version of the header the FMU was built with. */
typedef const char* fmi2GetTypesPlatformTYPE(void);
typedef const char* fmi2GetVersionTYPE(void);

/* FMI 2.0, 2.1.5: creation and destruction of an instance. */
typedef fmi2Component fmi2InstantiateTYPE(fmi2String instanceName, fmi2Type fmuType, fmi2String fmuGUID,
                                          fmi2String fmuResourceLocation, const fmi2CallbackFunctions* functions,
                                          fmi2Boolean visible, fmi2Boolean loggingOn);
typedef void fmi2FreeInstanceTYPE(fmi2Component c);

/* FMI 2.0, 2.1.6: initialization, termination and reset. */
typedef fmi2Status fmi2SetupExperimentTYPE(fmi2Component c, fmi2Boolean toleranceDefined, fmi2Real tolerance,
                                           fmi2Real startTime, fmi2Boolean stopTimeDefined, fmi2Real stopTime);
typedef fmi2Status fmi2EnterInitializationModeTYPE(fmi2Component c);
typedef fmi2Status fmi2ExitInitializationModeTYPE(fmi2Component c);
typedef fmi2Status fmi2TerminateTYPE(fmi2Component c);
typedef fmi2Status fmi2ResetTYPE(fmi2Component c);

/* FMI 2.0, 2.1.7: getting and setting Real variable values by value reference. */
typedef fmi2Status fmi2GetRealTYPE(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]);
typedef fmi2Status fmi2SetRealTYPE(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                   const fmi2Real value[]);

/* FMI 2.0, 2.1.8: getting and setting the complete FMU state (capability canGetAndSetFMUstate). */
typedef fmi2Status fmi2GetFMUstateTYPE(fmi2Component c, fmi2FMUstate* FMUstate);
typedef fmi2Status fmi2SetFMUstateTYPE(fmi2Component c, fmi2FMUstate FMUstate);
typedef fmi2Status fmi2FreeFMUstateTYPE(fmi2Component c, fmi2FMUstate* FMUstate);

/* FMI 2.0, 4.2.2: one communication step from currentCommunicationPoint of length
 * communicationStepSize. */
typedef fmi2Status fmi2DoStepTYPE(fmi2Component c, fmi2Real currentCommunicationPoint,
                                  fmi2Real communicationStepSize, fmi2Boolean noSetFMUStatePriorToCurrentPoint);

#ifdef __cplusplus
}
#endif

#endif /* NETMC_PLANT_FMU_FMI2_API_H */
