//! Run-time choice of the widest SIMD the CPU has, for the school's branch-free passes.
//!
//! The passes are plain loops over `f32` arrays that LLVM vectorises. Compiled for the
//! baseline x86-64 target they get SSE2 (4 lanes); [`simd_dispatch!`] compiles the same body a
//! second time with AVX2 enabled (8 lanes) and picks it once the CPU says it has AVX2. No
//! `-C target-cpu=native`: the binary still runs on any x86-64 and on other architectures.

/// `simd_dispatch!(fn name(arg: Type, ...) => body_fn)` defines `name`, which calls the
/// `#[inline(always)]` function `body_fn` compiled with AVX2 when the CPU has it.
macro_rules! simd_dispatch {
    ($vis:vis fn $name:ident($($arg:ident: $ty:ty),* $(,)?) => $body:path) => {
        $vis fn $name($($arg: $ty),*) {
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "avx2")]
                fn with_avx2($($arg: $ty),*) {
                    $body($($arg),*)
                }
                if std::arch::is_x86_feature_detected!("avx2") {
                    // SAFETY: the CPU has AVX2, checked on the line above
                    return unsafe { with_avx2($($arg),*) };
                }
            }
            $body($($arg),*)
        }
    };
}

pub(super) use simd_dispatch;
