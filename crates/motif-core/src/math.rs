//! Transcendental functions that give the same bits on every platform.
//!
//! `f64::exp`, `f64::sin`, `f64::atan2` and the like call the platform's math library: glibc in a
//! native build, a Rust port of musl's in the WebAssembly build. The two round some results
//! differently, so the playground's points brush came out up to 1.4e-14 away from the same strokes
//! run natively (102 of 720 values). These functions come from the `libm` crate, the same code on
//! every target (and `exp` is written here, with plain arithmetic), so an engine's output bits no
//! longer depend on where it runs. Engine code calls
//! them instead of the `f64` methods (`clippy.toml` of each engine crate disallows those).
//! Square roots and arithmetic are exactly rounded by IEEE 754 everywhere and need no wrapper.

/// `e^x`, within 2 ulp of the exact value (tested against `libm::exp`).
///
/// The Gaussian kernels of the points engine call it more than anything else, and `libm::exp`
/// (which divides) made a synthesis 15–25 % slower than the platform's; this one reduces `x` by
/// multiples of ln 2 / 32, looks the fraction's power of two up in a table and needs only a
/// degree-6 polynomial on |r| ≤ ln 2 / 64 (truncation error below 4e-18), with plain arithmetic
/// that every IEEE 754 target rounds alike.
#[inline]
pub fn exp(x: f64) -> f64 {
    // 1.5 × 2^52: adding and subtracting it rounds to the nearest integer (ties to even).
    const SHIFTER: f64 = 6_755_399_441_055_744.0;
    if x.is_nan() {
        return x;
    }
    if x >= 709.782_712_893_384 {
        return f64::INFINITY;
    }
    if x < -745.133_219_101_941_2 {
        return 0.0;
    }
    let kd = (x * THIRTY_TWO_OVER_LN2 + SHIFTER) - SHIFTER;
    let k = kd as i64;
    // Cody and Waite: the high part has 21 significant bits, so `kd × HI` is exact.
    let r = (x - kd * LN2_OVER_32_HI) - kd * LN2_OVER_32_LO;
    let p = 1.0 + r * (1.0 + r * (0.5 + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    let t = TWO_TO_J_OVER_32[(k & 31) as usize] * p;
    let m = k >> 5;
    if m > 1023 {
        (t * 2.0) * power_of_two(m - 1)
    } else if m < -1022 {
        // Subnormal results: two scalings, the second one rounding once into the subnormal range.
        (t * power_of_two(m + 1000)) * power_of_two(-1000)
    } else {
        t * power_of_two(m)
    }
}

/// `2^m` for a normal exponent (−1022 ≤ m ≤ 1023).
#[inline]
fn power_of_two(m: i64) -> f64 {
    f64::from_bits(((m + 1023) as u64) << 52)
}

/// `2^(j/32)`, correctly rounded (computed to 60 digits, then rounded once).
#[allow(clippy::excessive_precision, reason = "the table is written with the digits it was computed to")]
const TWO_TO_J_OVER_32: [f64; 32] = [
    1.0,
    1.0218971486541166,
    1.0442737824274138,
    1.0671404006768237,
    1.0905077326652577,
    1.1143867425958924,
    1.1387886347566916,
    1.1637248587775775,
    1.189207115002721,
    1.215247359980469,
    1.241857812073484,
    1.2690509571917332,
    1.2968395546510096,
    1.3252366431597413,
    1.3542555469368927,
    1.383909881963832,
    std::f64::consts::SQRT_2,
    1.4451808069770467,
    1.4768261459394993,
    1.5091644275934228,
    1.5422108254079407,
    1.5759808451078865,
    1.6104903319492543,
    1.645755478153965,
    1.681792830507429,
    1.718619298122478,
    1.7562521603732995,
    1.7947090750031072,
    1.8340080864093424,
    1.8741676341103,
    1.9152065613971474,
    1.9571441241754002,
];
/// ln 2 / 32 split for Cody–Waite reduction: a high part with 21 significant bits and the rest.
const LN2_OVER_32_HI: f64 = 0.021660834550857544;
const LN2_OVER_32_LO: f64 = 1.4841640746973977e-08;
/// 32 / ln 2.
const THIRTY_TWO_OVER_LN2: f64 = 46.16624130844683;

/// Sine (radians).
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// Cosine (radians).
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// Sine and cosine (radians) at once.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The angle of `(x, y)` from the x axis, in (−π, π].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// Arc cosine (radians).
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// `x^y`.
#[inline]
pub fn powf(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// Cube root.
#[inline]
pub fn cbrt(x: f64) -> f64 {
    libm::cbrt(x)
}

/// Base-10 logarithm.
#[inline]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// Natural logarithm.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// Arc tangent (radians), in [−π/2, π/2].
#[inline]
pub fn atan(x: f64) -> f64 {
    libm::atan(x)
}

/// Hyperbolic sine.
#[inline]
pub fn sinh(x: f64) -> f64 {
    libm::sinh(x)
}

/// `√(x² + y²)` without undue overflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// Sine of an `f32` (radians).
#[inline]
pub fn sin_f32(x: f32) -> f32 {
    libm::sinf(x)
}

/// Cosine of an `f32` (radians).
#[inline]
pub fn cos_f32(x: f32) -> f32 {
    libm::cosf(x)
}

/// `x.round()` (half away from zero) for finite `x` in `[0, 2^24)`, without its call into the
/// math library (`round` is no SSE2 instruction; it showed in the profiles of the 8-bit
/// conversions): `x as u32` truncates exactly there, `x − trunc(x)` is exact, and comparing it with
/// one half decides as `round` does (tested against it). Outside that range the value is
/// meaningless; callers pass clamped or bounded values.
#[inline]
pub fn round_non_negative(x: f32) -> f32 {
    let truncated = x as u32 as f32;
    // Added, not branched on: a half is as likely as not, so a branch would mispredict often.
    truncated + f32::from(u8::from(x - truncated >= 0.5))
}

/// `v` clamped to `[0, 1]` as a byte, `(v · 255).round()` ([`round_non_negative`]); NaN gives 0,
/// as the cast of `round`'s NaN does.
#[inline]
pub fn unit_to_byte(v: f32) -> u8 {
    round_non_negative(v.clamp(0.0, 1.0) * 255.0) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against `f32::round` on every float of `[0, 2)` at a stride, at the halves of `[0, 70 000)`
    /// and a few ulps around them, and on the bytes' boundaries of [`unit_to_byte`].
    #[test]
    fn rounding_without_libm_is_round() {
        let check = |x: f32| assert_eq!(round_non_negative(x).to_bits(), x.round().to_bits(), "{x:e}");
        (0..0x4000_0000_u32).step_by(997).map(f32::from_bits).for_each(check);
        for k in 0..70_000_u32 {
            let half = k as f32 + 0.5;
            let bits = half.to_bits();
            (bits - 3..=bits + 3).map(f32::from_bits).for_each(check);
        }
        for k in 0..=255_u32 {
            let boundary = (k as f32 + 0.5) / 255.0;
            for v in (boundary.to_bits() - 4..=boundary.to_bits() + 4).map(f32::from_bits) {
                assert_eq!(unit_to_byte(v), (v.clamp(0.0, 1.0) * 255.0).round() as u8, "{v:e}");
            }
        }
        assert_eq!((unit_to_byte(f32::NAN), unit_to_byte(-1.0), unit_to_byte(2.0)), (0, 0, 255));
    }

    /// Distance in units in the last place.
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    #[test]
    fn exp_is_within_two_ulp_of_libm_everywhere() {
        let mut worst = 0;
        // A dense sweep over the kernels' range, and a coarse one over the whole finite range.
        for i in 0..2_000_000 {
            let x = -60.0 + 70.0 * f64::from(i) / 2_000_000.0;
            worst = worst.max(ulps(exp(x), libm::exp(x)));
        }
        for i in 0..200_000 {
            let x = -745.0 + 1454.0 * f64::from(i) / 200_000.0;
            let (a, b) = (exp(x), libm::exp(x));
            assert!(
                ulps(a, b) <= 2 || (b < f64::MIN_POSITIVE && (a - b).abs() <= f64::MIN_POSITIVE * f64::EPSILON * 4.0),
                "{x}: {a} {b}"
            );
        }
        assert!(worst <= 2, "worst {worst} ulp");
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(exp(-800.0), 0.0);
        assert_eq!(exp(710.0), f64::INFINITY);
        assert!(exp(f64::NAN).is_nan());
        assert_eq!(exp(f64::NEG_INFINITY), 0.0);
        assert!(exp(709.7) < f64::INFINITY && exp(709.7) > 1e308);
        assert!(exp(-744.0) > 0.0);
    }

    #[test]
    fn values_are_the_functions() {
        // Exact cases, and values within an ulp or two of the true results.
        assert_eq!(exp(0.0), 1.0);
        assert_eq!(hypot(3.0, 4.0), 5.0);
        assert_eq!(cbrt(27.0), 3.0);
        assert_eq!(log10(1000.0), 3.0);
        assert_eq!(powf(2.0, 10.0), 1024.0);
        assert!((exp(1.0) - std::f64::consts::E).abs() <= 2.0 * f64::EPSILON * std::f64::consts::E);
        let (s, c) = sin_cos(0.7);
        assert_eq!((s, c), (sin(0.7), cos(0.7)));
        assert!((s * s + c * c - 1.0).abs() < 4.0 * f64::EPSILON);
        assert!((atan2(1.0, 1.0) - std::f64::consts::FRAC_PI_4).abs() < 2.0 * f64::EPSILON);
        assert!((acos(-1.0) - std::f64::consts::PI).abs() < 2.0 * f64::EPSILON);
    }
}
