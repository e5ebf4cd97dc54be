//! C's `printf("%g")`, which every SPD generator prints its numbers with: six
//! significant digits, exponent form below 1e-4 and from 1e6 on, trailing
//! zeros dropped.

/// `x` as C's `%g` prints it (precision 6).
pub fn fmt_g(x: f64) -> String {
    const PRECISION: i32 = 6;
    if x.is_nan() {
        return if x.is_sign_negative() { "-nan" } else { "nan" }.to_string();
    }
    if x.is_infinite() {
        return if x < 0.0 { "-inf" } else { "inf" }.to_string();
    }
    if x == 0.0 {
        return if x.is_sign_negative() { "-0" } else { "0" }.to_string();
    }
    // The exponent after rounding to PRECISION digits decides the style.
    let exp_form = format!("{:.*e}", (PRECISION - 1) as usize, x);
    let (mantissa, exponent) = exp_form.split_once('e').expect("LowerExp always has an exponent");
    let exponent: i32 = exponent.parse().expect("LowerExp exponent is an integer");
    if (-4..PRECISION).contains(&exponent) {
        let fixed = format!("{:.*}", (PRECISION - 1 - exponent) as usize, x);
        strip_zeros(&fixed).to_string()
    } else {
        let sign = if exponent < 0 { '-' } else { '+' };
        format!("{}e{}{:02}", strip_zeros(mantissa), sign, exponent.abs())
    }
}

fn strip_zeros(number: &str) -> &str {
    if number.contains('.') { number.trim_end_matches('0').trim_end_matches('.') } else { number }
}

#[cfg(test)]
mod tests {
    use super::fmt_g;

    #[test]
    fn matches_c_printf() {
        let cases = [
            (0.0, "0"),
            (-0.0, "-0"),
            (1.0, "1"),
            (0.5, "0.5"),
            (100000.0, "100000"),
            (1e6, "1e+06"),
            (123456.7, "123457"),
            (999999.5, "1e+06"),
            (0.0001, "0.0001"),
            (0.00001234, "1.234e-05"),
            (-2.55836e-17, "-2.55836e-17"),
            (3.0827, "3.0827"),
            (0.272165526, "0.272166"),
            (1.0 / 3.0, "0.333333"),
            (-12.0, "-12"),
            (1e100, "1e+100"),
            (0.000099999999, "0.0001"),
        ];
        for (x, want) in cases {
            assert_eq!(fmt_g(x), want, "fmt_g({x:e})");
        }
    }
}
