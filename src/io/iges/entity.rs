//! The parameter data of IGES entities: free-format parameters with Hollerith strings, reals
//! with `D` exponents, the delimiters of the global section, and the conversion of entity 128
//! (one-span B-spline surface) back into a Bezier patch.

use crate::bezier::BezierPatch;

/// Splits free-format IGES data into parameters, honouring Hollerith strings; stops at the
/// record delimiter. Returns `None` when the record delimiter is missing or a string is cut.
pub(super) fn split_params(
    data: &str,
    pd: char,
    rd: char,
) -> std::result::Result<Vec<String>, String> {
    let b: Vec<char> = data.chars().collect();
    let mut params = Vec::new();
    let mut k = 0;
    loop {
        // One parameter: optional blanks, then a Hollerith string or plain text.
        while k < b.len() && b[k] == ' ' {
            k += 1;
        }
        let mut j = k;
        while j < b.len() && b[j].is_ascii_digit() {
            j += 1;
        }
        let value;
        if j > k && j < b.len() && b[j] == 'H' {
            let n: usize = b[k..j]
                .iter()
                .collect::<String>()
                .parse()
                .map_err(|_| "bad Hollerith count".to_string())?;
            let end = j + 1 + n;
            if end > b.len() {
                return Err(format!("Hollerith string {}H runs past the data", n));
            }
            value = b[j + 1..end].iter().collect::<String>();
            k = end;
            while k < b.len() && b[k] == ' ' {
                k += 1;
            }
        } else {
            let mut e = k;
            while e < b.len() && b[e] != pd && b[e] != rd {
                e += 1;
            }
            value = b[k..e].iter().collect::<String>().trim().to_string();
            k = e;
        }
        params.push(value);
        match b.get(k) {
            Some(&c) if c == pd => k += 1,
            Some(&c) if c == rd => return Ok(params),
            Some(&c) => return Err(format!("unexpected '{c}' after parameter {}", params.len())),
            None => return Err("the record delimiter is missing".to_string()),
        }
    }
}

pub(super) fn parse_real(s: &str) -> Option<f64> {
    let t: String = s
        .trim()
        .chars()
        .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
        .collect();
    t.parse::<f64>().ok().filter(|x| x.is_finite())
}

/// The parameter and record delimiters declared at the start of the global section.
pub(super) fn global_delimiters(g: &str) -> std::result::Result<(char, char), String> {
    let c: Vec<char> = g.chars().collect();
    let mut k = 0;
    let mut pd = ',';
    if c.len() >= 3 && c[0] == '1' && c[1] == 'H' {
        pd = c[2];
        k = 3;
    }
    match c.get(k) {
        Some(&x) if x == pd => k += 1,
        _ => {
            return Err(
                "global section must start with the parameter delimiter (e.g. '1H,,')".into(),
            );
        }
    }
    let mut rd = ';';
    if c.len() >= k + 3 && c[k] == '1' && c[k + 1] == 'H' {
        rd = c[k + 2];
    }
    if pd == rd {
        return Err("parameter and record delimiters are the same character".into());
    }
    Ok((pd, rd))
}

/// Why an entity could not be read: bad data, or valid data fairsub does not read.
pub(super) enum Bad {
    Parse(String),
    Unsupported(String),
}

/// Converts the parameters of entity 128 into a Bezier patch.
pub(super) fn surface_128(params: &[String]) -> std::result::Result<BezierPatch, Bad> {
    let mut k = 0usize;
    let mut next = |what: &str| -> std::result::Result<&str, Bad> {
        let p = params.get(k).ok_or_else(|| {
            Bad::Parse(format!("parameters end at {k} where {what} was expected"))
        })?;
        k += 1;
        Ok(p.as_str())
    };
    let ty = next("the entity type")?;
    if ty.trim() != "128" {
        return Err(Bad::Parse(format!(
            "parameter data starts with '{ty}', not 128"
        )));
    }
    let mut int = |what: &str, max: i64| -> std::result::Result<usize, Bad> {
        let s = next(what)?;
        match s.trim().parse::<i64>() {
            Ok(v) if (0..=max).contains(&v) => Ok(v as usize),
            _ => Err(Bad::Parse(format!(
                "{what} is '{s}'; expected an integer in 0..={max}"
            ))),
        }
    };
    let k1 = int("K1", 10_000)?;
    let k2 = int("K2", 10_000)?;
    let m1 = int("M1", 64)?;
    let m2 = int("M2", 64)?;
    let mut props = [0usize; 5];
    for (n, p) in props.iter_mut().enumerate() {
        *p = int(&format!("PROP{}", n + 1), 1)?;
    }
    if k1 != m1 || k2 != m2 {
        return Err(Bad::Unsupported(format!(
            "B-spline surface with K1 = {k1}, M1 = {m1}, K2 = {k2}, M2 = {m2} has several spans; only single-span (Bezier) surfaces are read"
        )));
    }
    let mut real = |what: &str| -> std::result::Result<f64, Bad> {
        let s = next(what)?;
        parse_real(s).ok_or_else(|| Bad::Parse(format!("{what} is '{s}', not a real number")))
    };
    let mut knots = |m: usize, name: &str| -> std::result::Result<(f64, f64), Bad> {
        let v: Vec<f64> = (0..2 * m + 2)
            .map(|q| real(&format!("knot {name}({})", q as i64 - m as i64)))
            .collect::<std::result::Result<_, _>>()?;
        let (a, b) = (v[0], v[2 * m + 1]);
        let clamped = v[..=m].iter().all(|&x| x == a) && v[m + 1..].iter().all(|&x| x == b);
        if !clamped || a >= b {
            return Err(Bad::Unsupported(format!(
                "knots {name} = {v:?} are not those of one Bezier span (a repeated {} times, then b > a)",
                m + 1
            )));
        }
        Ok((a, b))
    };
    let (s0, s1) = knots(m1, "S")?;
    let (t0, t1) = knots(m2, "T")?;
    let n = (k1 + 1) * (k2 + 1);
    let mut w0 = None;
    for q in 0..n {
        let w = real(&format!("weight {q}"))?;
        let w0 = *w0.get_or_insert(w);
        if w <= 0.0 || (w - w0).abs() > 1e-12 * w0 {
            return Err(Bad::Unsupported(format!(
                "weights {w0} and {w} differ (or are not positive): rational surfaces are not read"
            )));
        }
    }
    let mut pts = vec![[0.0; 3]; n];
    for (q, pt) in pts.iter_mut().enumerate() {
        for (c, x) in pt.iter_mut().enumerate() {
            *x = real(&format!(
                "coordinate {} of control point {q}",
                ["X", "Y", "Z"][c]
            ))?;
        }
    }
    let range = [real("U(0)")?, real("U(1)")?, real("V(0)")?, real("V(1)")?];
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + x.abs().max(y.abs()));
    if !(close(range[0], s0) && close(range[1], s1) && close(range[2], t0) && close(range[3], t1)) {
        return Err(Bad::Unsupported(format!(
            "parameter range {range:?} is not the full knot range [{s0}, {s1}] x [{t0}, {t1}]"
        )));
    }
    // Control point (i, j) is number j * (K1 + 1) + i; fairsub stores b[i][j] at i * (K2+1) + j.
    let mut cps = vec![[0.0; 3]; n];
    for j in 0..=k2 {
        for i in 0..=k1 {
            cps[i * (k2 + 1) + j] = pts[j * (k1 + 1) + i];
        }
    }
    Ok(BezierPatch {
        deg_u: k1,
        deg_v: k2,
        cps,
        weights: None,
    })
}
