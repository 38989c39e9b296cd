//! Empirical bedload laws of the form qs* = a (theta - theta_c)^(3/2), the curves a study
//! of qs* against the Shields number is held against. They come from flume data and
//! earlier fits, not from a model the solvers use.

/// One law qs* = a (theta - theta_c)^(3/2), zero below the threshold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransportLaw {
    /// authors, as in a figure's legend
    pub name: &'static str,
    /// the publication and where in it
    pub source: &'static str,
    /// coefficient a
    pub a: f64,
    /// threshold Shields number theta_c
    pub theta_c: f64,
}

impl TransportLaw {
    /// qs* at the Shields number `theta`.
    pub fn qs_star(&self, theta: f64) -> f64 {
        self.a * (theta - self.theta_c).max(0.0).powf(1.5)
    }

    /// The law as a legend reads it, e.g. `Meyer-Peter & Mueller 8 (theta - 0.047)^1.5`.
    pub fn label(&self) -> String {
        format!("{} {} (theta - {})^1.5", self.name, self.a, self.theta_c)
    }
}

/// The classic laws of bedload and sheet flow.
pub const CLASSIC: [TransportLaw; 3] = [
    TransportLaw { name: "Meyer-Peter & Mueller", source: "Meyer-Peter & Mueller 1948", a: 8.0, theta_c: 0.047 },
    // the corrected fit of the same flume data
    TransportLaw { name: "Wong & Parker", source: "Wong & Parker 2006", a: 3.97, theta_c: 0.0495 },
    // sheet flow, with the threshold that Maurin et al. 2015 draw in their figure 6
    TransportLaw { name: "Wilson", source: "Wilson 1987; Maurin et al. 2015 figure 6", a: 11.8, theta_c: 0.04 },
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_and_values() {
        let labels: Vec<String> = CLASSIC.iter().map(TransportLaw::label).collect();
        assert_eq!(
            labels,
            [
                "Meyer-Peter & Mueller 8 (theta - 0.047)^1.5",
                "Wong & Parker 3.97 (theta - 0.0495)^1.5",
                "Wilson 11.8 (theta - 0.04)^1.5",
            ]
        );
        // 8 (1.047 - 0.047)^1.5 = 8, nothing below the threshold
        assert!((CLASSIC[0].qs_star(1.047) - 8.0).abs() < 1e-12);
        assert_eq!(CLASSIC[1].qs_star(0.03), 0.0);
    }
}
