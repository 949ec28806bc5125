//! Four f32 lanes for the BVH's box and triangle tests: SSE on x86_64 (part of its baseline, so no
//! runtime detection is needed), plain arrays elsewhere. Every operation is the IEEE operation of
//! the scalar code lane by lane, so vector and scalar tests give bit-identical results; `min` and
//! `max` are the selects `a < b ? a : b` and `a > b ? a : b`, which keep `b` when `a` is NaN.

#[cfg(target_arch = "x86_64")]
mod imp {
    use std::arch::x86_64::*;

    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub struct F4(__m128);

    /// Methods `name(self, o) -> Out` that apply one SSE intrinsic to both operands' lanes.
    macro_rules! lanewise {
        ($($name:ident -> $out:ident = $intr:ident;)*) => {
            $(
                #[inline(always)]
                pub fn $name(self, o: Self) -> $out {
                    // SAFETY: SSE is part of the x86_64 baseline.
                    $out(unsafe { $intr(self.0, o.0) })
                }
            )*
        };
    }

    /// A lane mask (all bits set where true).
    #[derive(Clone, Copy)]
    #[repr(transparent)]
    pub struct M4(__m128);

    impl F4 {
        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            // SAFETY: SSE is part of the x86_64 baseline.
            Self(unsafe { _mm_set1_ps(x) })
        }
        /// The SSE register (for `F8`, which joins two).
        #[inline(always)]
        pub(crate) fn raw(self) -> __m128 {
            self.0
        }
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            // SAFETY: SSE baseline; `a` is four readable f32s.
            Self(unsafe { _mm_loadu_ps(a.as_ptr()) })
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            let mut a = [0.0; 4];
            // SAFETY: SSE baseline; `a` is four writable f32s.
            unsafe { _mm_storeu_ps(a.as_mut_ptr(), self.0) };
            a
        }
        /// Truncated towards zero (for values in the i32 range).
        #[inline(always)]
        pub fn to_i32(self) -> [i32; 4] {
            // SAFETY: SSE2 baseline; `__m128i` and `[i32; 4]` have the same size.
            unsafe { std::mem::transmute::<__m128i, [i32; 4]>(_mm_cvttps_epi32(self.0)) }
        }
        #[inline(always)]
        pub fn sqrt(self) -> Self {
            // SAFETY: SSE baseline; _mm_sqrt_ps is the correctly rounded IEEE square root.
            Self(unsafe { _mm_sqrt_ps(self.0) })
        }
        /// The magnitude (the sign bit cleared).
        #[inline(always)]
        pub fn abs(self) -> Self {
            // SAFETY: SSE baseline.
            Self(unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), self.0) })
        }
        lanewise! {
            min -> F4 = _mm_min_ps;
            max -> F4 = _mm_max_ps;
            le -> M4 = _mm_cmple_ps;
            lt -> M4 = _mm_cmplt_ps;
            gt -> M4 = _mm_cmpgt_ps;
            eq -> M4 = _mm_cmpeq_ps;
        }
    }

    impl M4 {
        /// The SSE register (for `M8`, which joins two).
        #[inline(always)]
        pub(crate) fn raw(self) -> __m128 {
            self.0
        }
        lanewise! {
            or -> M4 = _mm_or_ps;
            and -> M4 = _mm_and_ps;
        }
        /// `self && !o`.
        #[inline(always)]
        pub fn and_not(self, o: Self) -> Self {
            // SAFETY: SSE baseline.
            Self(unsafe { _mm_andnot_ps(o.0, self.0) })
        }
        /// Bit `l` set where lane `l` is true.
        #[inline(always)]
        pub fn bits(self) -> u32 {
            // SAFETY: SSE baseline.
            unsafe { _mm_movemask_ps(self.0) as u32 }
        }
        /// `a` where true, `b` elsewhere.
        #[inline(always)]
        pub fn select(self, a: F4, b: F4) -> F4 {
            // SAFETY: SSE baseline (and, andnot, or: SSE4.1's blend is not in the baseline).
            F4(unsafe { _mm_or_ps(_mm_and_ps(self.0, a.0), _mm_andnot_ps(self.0, b.0)) })
        }
    }

    macro_rules! binop {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl std::ops::$tr for F4 {
                type Output = F4;
                #[inline(always)]
                fn $f(self, o: F4) -> F4 {
                    // SAFETY: SSE baseline.
                    F4(unsafe { $intr(self.0, o.0) })
                }
            }
        };
    }
    binop!(Add, add, _mm_add_ps);
    binop!(Sub, sub, _mm_sub_ps);
    binop!(Mul, mul, _mm_mul_ps);
    binop!(Div, div, _mm_div_ps);
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    #[derive(Clone, Copy)]
    pub struct F4([f32; 4]);

    #[derive(Clone, Copy)]
    pub struct M4([bool; 4]);

    impl F4 {
        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            Self([x; 4])
        }
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            Self(*a)
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            self.0
        }
        /// Truncated towards zero (for values in the i32 range).
        #[inline(always)]
        pub fn to_i32(self) -> [i32; 4] {
            self.0.map(|x| x as i32)
        }
        #[inline(always)]
        pub fn sqrt(self) -> Self {
            Self(self.0.map(f32::sqrt))
        }
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(self.0.map(f32::abs))
        }
        #[inline(always)]
        fn zip(self, o: Self, f: impl Fn(f32, f32) -> f32) -> Self {
            Self(std::array::from_fn(|l| f(self.0[l], o.0[l])))
        }
        #[inline(always)]
        fn cmp(self, o: Self, f: impl Fn(f32, f32) -> bool) -> M4 {
            M4(std::array::from_fn(|l| f(self.0[l], o.0[l])))
        }
        #[inline(always)]
        pub fn min(self, o: Self) -> Self {
            self.zip(o, |a, b| if a < b { a } else { b })
        }
        #[inline(always)]
        pub fn max(self, o: Self) -> Self {
            self.zip(o, |a, b| if a > b { a } else { b })
        }
        #[inline(always)]
        pub fn le(self, o: Self) -> M4 {
            self.cmp(o, |a, b| a <= b)
        }
        #[inline(always)]
        pub fn lt(self, o: Self) -> M4 {
            self.cmp(o, |a, b| a < b)
        }
        #[inline(always)]
        pub fn gt(self, o: Self) -> M4 {
            self.cmp(o, |a, b| a > b)
        }
        #[inline(always)]
        pub fn eq(self, o: Self) -> M4 {
            self.cmp(o, |a, b| a == b)
        }
    }

    impl M4 {
        #[inline(always)]
        pub fn or(self, o: Self) -> Self {
            Self(std::array::from_fn(|l| self.0[l] || o.0[l]))
        }
        #[inline(always)]
        pub fn and(self, o: Self) -> Self {
            Self(std::array::from_fn(|l| self.0[l] && o.0[l]))
        }
        #[inline(always)]
        pub fn and_not(self, o: Self) -> Self {
            Self(std::array::from_fn(|l| self.0[l] && !o.0[l]))
        }
        #[inline(always)]
        pub fn bits(self) -> u32 {
            (0..4).fold(0, |b, l| b | (self.0[l] as u32) << l)
        }
        #[inline(always)]
        pub fn select(self, a: super::F4, b: super::F4) -> super::F4 {
            let (a, b) = (a.to_array(), b.to_array());
            super::F4::load(&std::array::from_fn(
                |l| if self.0[l] { a[l] } else { b[l] },
            ))
        }
    }

    macro_rules! binop {
        ($tr:ident, $f:ident, $op:tt) => {
            impl std::ops::$tr for F4 {
                type Output = F4;
                #[inline(always)]
                fn $f(self, o: F4) -> F4 {
                    self.zip(o, |a, b| a $op b)
                }
            }
        };
    }
    binop!(Add, add, +);
    binop!(Sub, sub, -);
    binop!(Mul, mul, *);
    binop!(Div, div, /);
}

pub use imp::{F4, M4};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_max_keep_the_second_operand_on_nan() {
        let a = F4::load(&[f32::NAN, 1.0, 3.0, f32::NAN]);
        let b = F4::load(&[2.0, 2.0, 2.0, f32::NAN]);
        let mn = a.min(b).to_array();
        let mx = a.max(b).to_array();
        assert_eq!(&mn[..3], &[2.0, 1.0, 2.0]);
        assert_eq!(&mx[..3], &[2.0, 2.0, 3.0]);
        assert!(mn[3].is_nan() && mx[3].is_nan());
        assert_eq!(a.le(b).bits(), 0b0010);
        assert_eq!(a.gt(b).bits(), 0b0100);
    }

    #[test]
    fn sqrt_abs_and_select_are_the_scalar_ones_lane_by_lane() {
        let a = F4::load(&[4.0, -2.5, 0.0, 1e-30]);
        let b = F4::load(&[9.0, 7.0, -0.0, 3.0]);
        assert_eq!(
            b.abs().sqrt().to_array(),
            [3.0, 7.0f32.sqrt(), 0.0, 3.0f32.sqrt()]
        );
        assert_eq!(a.abs().to_array(), [4.0, 2.5, 0.0, 1e-30]);
        assert!(a.sqrt().to_array()[1].is_nan());
        assert_eq!(a.lt(b).select(a, b).to_array(), [4.0, -2.5, -0.0, 1e-30]);
        assert_eq!(a.gt(b).select(a, b).to_array(), [9.0, 7.0, -0.0, 3.0]);
    }
}
