//! The lane arithmetic that SIMD code is written in once (the light BVH's bounds, the BVH's slab
//! test), for four lanes (`F4`: SSE, or arrays off x86_64) or eight (`F8`: AVX, x86_64 only, for
//! code reached from a function compiled for AVX after a runtime check). Every operation is the
//! IEEE one lane by lane, so both widths give the same bits in each lane.

use std::ops::{Add, Div, Mul, Sub};

use super::f4::{F4, M4};

/// f32 lanes and their comparisons.
pub trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self>
{
    /// A lane mask (true or false per lane).
    type Mask: LaneMask;
    /// The number of lanes.
    const N: usize;
    fn splat(x: f32) -> Self;
    /// The first `N` values of `a` (which holds at least `N`).
    fn load(a: &[f32]) -> Self;
    /// The lanes into the first `N` values of `out` (which holds at least `N`).
    fn store(self, out: &mut [f32]);
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    /// `self < o ? self : o` per lane (keeps `o` where `self` is NaN).
    fn min(self, o: Self) -> Self;
    /// `self > o ? self : o` per lane (keeps `o` where `self` is NaN).
    fn max(self, o: Self) -> Self;
    fn lt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    fn eq(self, o: Self) -> Self::Mask;
    /// Bit `l` set where lane `l` of `m` is true.
    fn bits(m: Self::Mask) -> u32;
    /// `a` where `m` is true, `b` elsewhere.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

/// The logic of lane masks.
pub trait LaneMask: Copy {
    fn or(self, o: Self) -> Self;
    fn and(self, o: Self) -> Self;
    /// `self && !o` per lane.
    fn and_not(self, o: Self) -> Self;
}

impl LaneMask for M4 {
    #[inline(always)]
    fn or(self, o: Self) -> Self {
        M4::or(self, o)
    }
    #[inline(always)]
    fn and(self, o: Self) -> Self {
        M4::and(self, o)
    }
    #[inline(always)]
    fn and_not(self, o: Self) -> Self {
        M4::and_not(self, o)
    }
}

impl Lanes for F4 {
    type Mask = M4;
    const N: usize = 4;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        F4::splat(x)
    }
    #[inline(always)]
    fn load(a: &[f32]) -> Self {
        F4::load(a[..4].try_into().expect("four values"))
    }
    #[inline(always)]
    fn store(self, out: &mut [f32]) {
        out[..4].copy_from_slice(&self.to_array());
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F4::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F4::abs(self)
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        F4::min(self, o)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        F4::max(self, o)
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M4 {
        F4::lt(self, o)
    }
    #[inline(always)]
    fn le(self, o: Self) -> M4 {
        F4::le(self, o)
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M4 {
        F4::gt(self, o)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M4 {
        F4::eq(self, o)
    }
    #[inline(always)]
    fn bits(m: M4) -> u32 {
        m.bits()
    }
    #[inline(always)]
    fn select(m: M4, a: Self, b: Self) -> Self {
        m.select(a, b)
    }
}

#[cfg(target_arch = "x86_64")]
pub use avx::{F8, M8};

/// Eight lanes in AVX registers. Only code that runs where the CPU has AVX may make or use them:
/// their methods are AVX instructions, inlined into the AVX-compiled caller.
#[cfg(target_arch = "x86_64")]
mod avx {
    use std::arch::x86_64::*;

    use super::{LaneMask, Lanes, F4, M4};

    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub struct F8(__m256);

    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub struct M8(__m256);

    // SAFETY (every `unsafe` block below): an `F8` or `M8` exists only in code reached from a
    // function compiled for AVX, called after a runtime check that the CPU has it (see the type's
    // doc), so its AVX instructions can run.

    impl F8 {
        /// Lanes 0-3 from `lo`, 4-7 from `hi`.
        #[inline(always)]
        pub fn halves(lo: F4, hi: F4) -> Self {
            Self(unsafe { _mm256_set_m128(hi.raw(), lo.raw()) })
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 8] {
            let mut a = [0.0; 8];
            unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) };
            a
        }
    }

    impl M8 {
        /// Lanes 0-3 from `lo`, 4-7 from `hi`.
        #[inline(always)]
        pub fn halves(lo: M4, hi: M4) -> Self {
            Self(unsafe { _mm256_set_m128(hi.raw(), lo.raw()) })
        }
    }

    macro_rules! binop {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl std::ops::$tr for F8 {
                type Output = F8;
                #[inline(always)]
                fn $f(self, o: F8) -> F8 {
                    F8(unsafe { $intr(self.0, o.0) })
                }
            }
        };
    }
    binop!(Add, add, _mm256_add_ps);
    binop!(Sub, sub, _mm256_sub_ps);
    binop!(Mul, mul, _mm256_mul_ps);
    binop!(Div, div, _mm256_div_ps);

    impl LaneMask for M8 {
        #[inline(always)]
        fn or(self, o: Self) -> Self {
            Self(unsafe { _mm256_or_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn and(self, o: Self) -> Self {
            Self(unsafe { _mm256_and_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn and_not(self, o: Self) -> Self {
            Self(unsafe { _mm256_andnot_ps(o.0, self.0) })
        }
    }

    impl Lanes for F8 {
        type Mask = M8;
        const N: usize = 8;
        #[inline(always)]
        fn splat(x: f32) -> Self {
            Self(unsafe { _mm256_set1_ps(x) })
        }
        #[inline(always)]
        fn load(a: &[f32]) -> Self {
            let a: &[f32; 8] = a[..8].try_into().expect("eight values");
            Self(unsafe { _mm256_loadu_ps(a.as_ptr()) })
        }
        #[inline(always)]
        fn store(self, out: &mut [f32]) {
            let out: &mut [f32; 8] = (&mut out[..8]).try_into().expect("eight values");
            unsafe { _mm256_storeu_ps(out.as_mut_ptr(), self.0) };
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            Self(unsafe { _mm256_sqrt_ps(self.0) })
        }
        #[inline(always)]
        fn abs(self) -> Self {
            Self(unsafe { _mm256_andnot_ps(_mm256_set1_ps(-0.0), self.0) })
        }
        // minps/maxps return the second operand where either is NaN, as SSE's do.
        #[inline(always)]
        fn min(self, o: Self) -> Self {
            Self(unsafe { _mm256_min_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn max(self, o: Self) -> Self {
            Self(unsafe { _mm256_max_ps(self.0, o.0) })
        }
        #[inline(always)]
        fn lt(self, o: Self) -> M8 {
            M8(unsafe { _mm256_cmp_ps::<_CMP_LT_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn le(self, o: Self) -> M8 {
            M8(unsafe { _mm256_cmp_ps::<_CMP_LE_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn gt(self, o: Self) -> M8 {
            M8(unsafe { _mm256_cmp_ps::<_CMP_GT_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn eq(self, o: Self) -> M8 {
            M8(unsafe { _mm256_cmp_ps::<_CMP_EQ_OQ>(self.0, o.0) })
        }
        #[inline(always)]
        fn bits(m: M8) -> u32 {
            unsafe { _mm256_movemask_ps(m.0) as u32 }
        }
        #[inline(always)]
        fn select(m: M8, a: Self, b: Self) -> Self {
            Self(unsafe { _mm256_blendv_ps(b.0, a.0, m.0) })
        }
    }
}
