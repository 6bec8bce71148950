//! The 34 entry points of an FMI 2.0 Co-Simulation FMU: resolved from a loaded shared library
//! ([`Functions::resolve`]) or taken from a library linked into this program
//! ([`linked_functions!`](crate::linked_functions)).

use fmi_sys::fmi2::*;
use libloading::Library;

/// Unwraps fmi-sys's `fmi2XxxTYPE = Option<unsafe extern "C" fn(…)>` to the function pointer.
pub trait Entry {
    type Fn: Copy;
}

impl<F: Copy> Entry for Option<F> {
    type Fn = F;
}

/// The function pointer of one of fmi-sys's `fmi2XxxTYPE`s.
pub type EntryPoint<T> = <T as Entry>::Fn;

macro_rules! functions {
    ($d:tt $($name:ident: $ty:ident,)*) => {
        /// The entry points of an FMI 2.0 Co-Simulation FMU, one field per function of the
        /// standard, named as it names them. Calling one is `unsafe`: the standard's contract
        /// (live component, valid arrays) is the caller's.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy)]
        pub struct Functions {
            $(pub $name: EntryPoint<$ty>,)*
        }

        impl Functions {
            /// Every entry point of `library`, or the names of those it does not export.
            ///
            /// # Safety
            /// The library's symbols of these names must have the signatures of the FMI 2.0
            /// headers (as any FMU's must).
            #[allow(non_snake_case)]
            pub unsafe fn resolve(library: &Library) -> Result<Self, Vec<&'static str>> {
                let mut missing = Vec::new();
                $(
                    // SAFETY: the caller vouches for the signature.
                    let $name = unsafe { library.get::<EntryPoint<$ty>>(stringify!($name).as_bytes()) }
                        .map(|symbol| *symbol)
                        .map_err(|_| missing.push(stringify!($name)));
                )*
                match ($($name,)*) {
                    ($(Ok($name),)*) => Ok(Self { $($name,)* }),
                    _ => Err(missing),
                }
            }
        }

        /// The [`Functions`] of an FMU linked into this program:
        /// `linked_functions!(my_crate::models::export)` names the module that defines the 34
        /// `fmi2*` functions (a signature that differs from the FMI 2.0 headers does not compile).
        #[macro_export]
        macro_rules! linked_functions {
            ($d($d module:ident)::+) => {{
                use $d($d module)::+ as exports;
                $crate::Functions {
                    $($name: exports::$name,)*
                }
            }};
        }
    };
}

functions! {$
    fmi2GetTypesPlatform: fmi2GetTypesPlatformTYPE,
    fmi2GetVersion: fmi2GetVersionTYPE,
    fmi2SetDebugLogging: fmi2SetDebugLoggingTYPE,
    fmi2Instantiate: fmi2InstantiateTYPE,
    fmi2FreeInstance: fmi2FreeInstanceTYPE,
    fmi2SetupExperiment: fmi2SetupExperimentTYPE,
    fmi2EnterInitializationMode: fmi2EnterInitializationModeTYPE,
    fmi2ExitInitializationMode: fmi2ExitInitializationModeTYPE,
    fmi2Terminate: fmi2TerminateTYPE,
    fmi2Reset: fmi2ResetTYPE,
    fmi2GetReal: fmi2GetRealTYPE,
    fmi2GetInteger: fmi2GetIntegerTYPE,
    fmi2GetBoolean: fmi2GetBooleanTYPE,
    fmi2GetString: fmi2GetStringTYPE,
    fmi2SetReal: fmi2SetRealTYPE,
    fmi2SetInteger: fmi2SetIntegerTYPE,
    fmi2SetBoolean: fmi2SetBooleanTYPE,
    fmi2SetString: fmi2SetStringTYPE,
    fmi2GetFMUstate: fmi2GetFMUstateTYPE,
    fmi2SetFMUstate: fmi2SetFMUstateTYPE,
    fmi2FreeFMUstate: fmi2FreeFMUstateTYPE,
    fmi2SerializedFMUstateSize: fmi2SerializedFMUstateSizeTYPE,
    fmi2SerializeFMUstate: fmi2SerializeFMUstateTYPE,
    fmi2DeSerializeFMUstate: fmi2DeSerializeFMUstateTYPE,
    fmi2GetDirectionalDerivative: fmi2GetDirectionalDerivativeTYPE,
    fmi2SetRealInputDerivatives: fmi2SetRealInputDerivativesTYPE,
    fmi2GetRealOutputDerivatives: fmi2GetRealOutputDerivativesTYPE,
    fmi2DoStep: fmi2DoStepTYPE,
    fmi2CancelStep: fmi2CancelStepTYPE,
    fmi2GetStatus: fmi2GetStatusTYPE,
    fmi2GetRealStatus: fmi2GetRealStatusTYPE,
    fmi2GetIntegerStatus: fmi2GetIntegerStatusTYPE,
    fmi2GetBooleanStatus: fmi2GetBooleanStatusTYPE,
    fmi2GetStringStatus: fmi2GetStringStatusTYPE,
}
