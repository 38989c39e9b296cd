//! Algebraic mixing-length turbulence closure (Prandtl, Li & Sawamoto, Berzi & Fraccarollo).

use saltus_core::closure::Family;
use saltus_core::{register_model, ColumnView, Describe, Field, Limit, Needs, Params, Turbulence};
use serde::{Deserialize, Serialize};

/// Which mixing-length profile [`MixingLength`] uses.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum MixingLengthForm {
    /// l_m = kappa z (law of the wall, clear fluid)
    Prandtl,
    /// l_m = kappa integral_0^z (1 - phi/phi_max) dz' (turbulence damped by the bed)
    #[default]
    LiSawamoto,
    /// l_m = max(coefficient d (phi_max - phi)^exponent, floor d) (fluid-particle turbulence)
    BerziFraccarollo,
}

impl MixingLengthForm {
    /// Paper and equation numbers of this form.
    pub fn source(self) -> &'static str {
        match self {
            Self::Prandtl => "Prandtl; Chassagne et al. 2023 eqs 2.7-2.8a",
            Self::LiSawamoto => "Chassagne et al. 2023 eqs 2.7-2.8; Maurin et al. 2015 eqs 4-5",
            Self::BerziFraccarollo => "Chassagne et al. 2023 eqs 2.8a and 4.2 (Berzi & Fraccarollo 2015)",
        }
    }

    /// The limits this form declares with von Karman constant `kappa`: l_m / z -> kappa at
    /// the wall in clear fluid for `prandtl` and `li_sawamoto` (whose integrand is 1 where
    /// phi = 0), none for `berzi_fraccarollo`, whose length in clear fluid is the constant
    /// max(coefficient phi_max^exponent, floor) d, whatever z.
    pub fn limits(self, kappa: f64) -> Vec<Limit> {
        match self {
            Self::Prandtl | Self::LiSawamoto => vec![Limit::WallLength { kappa }],
            Self::BerziFraccarollo => Vec::new(),
        }
    }

    /// The equation of this form, one line.
    pub fn equation(self) -> &'static str {
        match self {
            Self::Prandtl => "nu_t = l^2 |du/dz|, l = kappa z",
            Self::LiSawamoto => "nu_t = l^2 |du/dz|, l = kappa int_0^z (1 - phi/phi_max) dz'",
            Self::BerziFraccarollo => "nu_t = l^2 |du/dz|, l = max(coefficient d (phi_max - phi)^exponent, floor d)",
        }
    }
}

/// What the `li_sawamoto` integral takes inside the bed.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq, Eq, Params)]
#[serde(rename_all = "snake_case")]
pub enum PackedBed {
    /// every cell adds its own open fraction (1 - phi/phi_max), clamped at 0
    #[default]
    Cellwise,
    /// phi = phi_max in every cell below the highest cell at phi >= phi_max: the bed under
    /// its packed top adds nothing (Maurin's coupled fluid-DEM code, see [`MixingLength`])
    Packed,
}

/// Mixing-length eddy viscosity
///
/// nu_t = l_m^2 |du/dz|,  R_xz / (rho_f (1 - phi)) = nu_t du/dz, with l_m by `form`:
///
/// * `prandtl`: l_m = kappa z, z from the bottom wall (cell centre).
/// * `li_sawamoto`: l_m(z) = kappa integral_0^z (1 - phi(z')/phi_max) dz'.
/// * `berzi_fraccarollo`: l_m = max[coefficient d (phi_max - phi)^exponent, floor d].
///
/// * Source: Chassagne et al. 2023 eqs 2.7-2.8a,b (nu_t and Li & Sawamoto l_m) and eq 4.2
///   (Berzi & Fraccarollo 2015 l_m with the Ni & Capart 0.2 d floor); Maurin et al. 2015
///   eqs 4-5.
/// * Defaults: `form = "li_sawamoto"`, `kappa = 0.41`, `phi_max = 0.635`,
///   `coefficient = 3`, `exponent = 3`, `floor = 0.2` (the last three in units of d, used by
///   `berzi_fraccarollo` only; `phi_max` unused by `prandtl`).
/// * Valid range: `kappa` in (0, 1], `phi_max` in (0, 1), `coefficient` > 0,
///   `exponent` in [0, 10], `floor` >= 0. Every parameter is validated whatever the form.
///
/// Decisions:
/// * nu_t carries no (1 - phi) factor (Chassagne eq 2.8a). Maurin eq 4 writes
///   nu_t = eps l_m^2 |du/dz| and its fluid stress eps tau + R; Chassagne eq 2.7 puts the
///   same eps in front of (nu + nu_t). The solver applies that factor once, as in
///   Chassagne eq 2.7, so the kinematic Reynolds stress R_xz/(rho_f eps) the fluctuation
///   closures use is nu_t du/dz.
/// * `li_sawamoto` is integrated exactly for a phi piecewise constant over cells: the sum
///   over the full cells below plus the part of the current cell from its lower face to its
///   centre. Faces are accumulated from the wall (z = 0) with `dz`. The integrand is
///   clamped to [0, 1], so phi > phi_max (overpacked cells) never gives a negative length
///   and a negative undershoot of phi never gives l_m > kappa z. With phi = 0 everywhere it
///   reproduces `prandtl` exactly (bit for bit as long as every lower face lies within
///   [z/2, 2z] of the centre, true for any grid stretched by at most 2 between cells).
/// * `berzi_fraccarollo` clamps phi_max - phi at 0 before the power, so a bed above
///   phi_max has the floor length.
/// * Declared limits ([`MixingLengthForm::limits`]): l_m / z -> `kappa` at the wall in clear
///   fluid for `prandtl` and `li_sawamoto` (either `bed`); none for `berzi_fraccarollo`, a
///   length of the grains (in diameters) that does not vanish at the wall, so l_m / z
///   grows without bound as z -> 0.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Describe)]
#[serde(deny_unknown_fields, default)]
#[describe(
    name = "mixing_length",
    source = self.form.source(),
    equation = self.form.equation(),
    limits = self.form.limits(self.kappa)
)]
pub struct MixingLength {
    /// mixing-length profile
    pub form: MixingLengthForm,
    /// von Karman constant
    #[param(range = "(0, 1]", unit = "-")]
    pub kappa: f64,
    /// maximum packing fraction (li_sawamoto, berzi_fraccarollo)
    #[param(range = "(0, 1)", unit = "-")]
    pub phi_max: f64,
    /// mixing length scale in diameters (berzi_fraccarollo)
    #[param(range = "(0, inf)", unit = "d")]
    pub coefficient: f64,
    /// power of (phi_max - phi) (berzi_fraccarollo)
    #[param(range = "[0, 10]", unit = "-")]
    pub exponent: f64,
    /// minimal mixing length in diameters (berzi_fraccarollo)
    #[param(range = "[0, inf)", unit = "d")]
    pub floor: f64,
    /// what the li_sawamoto integral takes inside the bed
    pub bed: PackedBed,
}

impl Default for MixingLength {
    fn default() -> Self {
        Self {
            form: MixingLengthForm::LiSawamoto,
            kappa: 0.41,
            phi_max: 0.635,
            coefficient: 3.0,
            exponent: 3.0,
            floor: 0.2,
            bed: PackedBed::Cellwise,
        }
    }
}

impl MixingLength {
    /// Mixing length of `berzi_fraccarollo` at volume fraction `phi` for diameter `d`.
    #[inline]
    pub fn berzi_fraccarollo(&self, phi: f64, d: f64) -> f64 {
        let gap = (self.phi_max - phi).max(0.0);
        (self.coefficient * d * gap.powf(self.exponent)).max(self.floor * d)
    }

    /// Li & Sawamoto integrand (1 - phi/phi_max), clamped to [0, 1] (NaN gives 0).
    #[inline]
    fn open_fraction(&self, phi: f64) -> f64 {
        (1.0 - phi / self.phi_max).clamp(0.0, 1.0).max(0.0)
    }
}

#[typetag::serde(name = "mixing_length")]
impl Turbulence for MixingLength {
    fn provides(&self) -> Needs {
        Needs::of(&[Field::EddyViscosity, Field::ReynoldsStress])
    }

    fn mixing_length(&self, col: &ColumnView<'_>, out: &mut [f64]) {
        match self.form {
            MixingLengthForm::Prandtl => {
                for (o, &z) in out.iter_mut().zip(col.z) {
                    *o = self.kappa * z;
                }
            }
            MixingLengthForm::LiSawamoto => {
                // cells up to this index count as packed (none with `cellwise`)
                let packed = match self.bed {
                    PackedBed::Cellwise => None,
                    PackedBed::Packed => col.phi.iter().rposition(|&phi| phi >= self.phi_max),
                };
                // integral of the open fraction over the full cells below the current one
                let mut below = 0.0;
                // lower face of the current cell, from the wall
                let mut face = 0.0;
                for (i, (((o, &z), &dz), &phi)) in out.iter_mut().zip(col.z).zip(col.dz).zip(col.phi).enumerate() {
                    let f = if packed.is_some_and(|top| i <= top) { 0.0 } else { self.open_fraction(phi) };
                    *o = self.kappa * (below + f * (z - face));
                    below += f * dz;
                    face += dz;
                }
            }
            MixingLengthForm::BerziFraccarollo => {
                for (o, &phi) in out.iter_mut().zip(col.phi) {
                    *o = self.berzi_fraccarollo(phi, col.diameter);
                }
            }
        }
    }
}

register_model!(Family::Turbulence, "mixing_length", Turbulence, MixingLength);

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    const D: f64 = 1e-3;

    fn uniform(n: usize, dz: f64) -> (Vec<f64>, Vec<f64>) {
        ((0..n).map(|i| (i as f64 + 0.5) * dz).collect(), vec![dz; n])
    }

    fn lengths(m: &MixingLength, z: &[f64], dz: &[f64], phi: &[f64]) -> Vec<f64> {
        let dudz = vec![1.0; z.len()];
        let col = ColumnView { z, dz, phi, dudz: &dudz, diameter: D, nu_f: 1e-6, transported: &[] };
        let mut out = vec![f64::NAN; z.len()];
        m.mixing_length(&col, &mut out);
        out
    }

    fn with_form(form: MixingLengthForm) -> MixingLength {
        MixingLength { form, ..MixingLength::default() }
    }

    #[test]
    fn prandtl_is_kappa_z() {
        let m = with_form(MixingLengthForm::Prandtl);
        let (z, dz) = uniform(50, 2e-3);
        let phi = vec![0.3; 50];
        for (l, zi) in lengths(&m, &z, &dz, &phi).iter().zip(&z) {
            assert_eq!(*l, 0.41 * zi);
        }
    }

    #[test]
    fn li_sawamoto_step_profile_is_kappa_z_minus_zb() {
        // phi = phi_max below z_b = 20 dz (a cell face), 0 above: l = kappa (z - z_b) above
        // and 0 inside the bed, exactly at the cell centres.
        let m = MixingLength::default();
        let (z, dz) = uniform(100, 1e-3);
        let zb = 20.0 * 1e-3;
        let phi: Vec<f64> = z.iter().map(|&zi| if zi < zb { m.phi_max } else { 0.0 }).collect();
        for (l, zi) in lengths(&m, &z, &dz, &phi).iter().zip(&z) {
            let exact = 0.41 * (zi - zb).max(0.0);
            assert!((l - exact).abs() <= 1e-14 * 0.41 * zi, "z = {zi}: {l} vs {exact}");
        }
    }

    #[test]
    fn li_sawamoto_bed_at_phi_max_and_above_is_zero() {
        let m = MixingLength::default();
        let (z, dz) = uniform(30, 1e-3);
        let mut phi = vec![m.phi_max; 30];
        phi[5] = 0.7; // overpacked cell: clamped, never negative
        assert!(lengths(&m, &z, &dz, &phi).iter().all(|&l| l == 0.0));
    }

    #[test]
    fn li_sawamoto_packed_bed_ignores_loose_cells_under_its_top() {
        // a bed at phi_max up to z_b = 20 dz with loose cells (the layering over a rough
        // bottom) at 2-4 dz, clear fluid above: with `packed` l_m = 0 in the bed and
        // kappa (z - z_b) above, as without the loose cells; `cellwise` adds their open
        // fraction 3 dz (1 - 0.5/phi_max) to every length above them
        let packed = MixingLength { bed: PackedBed::Packed, ..MixingLength::default() };
        let cellwise = MixingLength::default();
        let dz0 = 1e-3;
        let (z, dz) = uniform(100, dz0);
        let zb = 20.0 * dz0;
        let phi: Vec<f64> = (0..100)
            .map(|i| {
                if (2..5).contains(&i) {
                    0.5
                } else if i < 20 {
                    packed.phi_max
                } else {
                    0.0
                }
            })
            .collect();
        let offset = 0.41 * 3.0 * dz0 * (1.0 - 0.5 / cellwise.phi_max);
        let (lp, lc) = (lengths(&packed, &z, &dz, &phi), lengths(&cellwise, &z, &dz, &phi));
        for i in 0..100 {
            let exact = 0.41 * (z[i] - zb).max(0.0);
            assert!((lp[i] - exact).abs() <= 1e-14 * 0.41 * z[i], "z = {}: {} vs {exact}", z[i], lp[i]);
            if i >= 5 {
                assert_relative_eq!(lc[i], exact + offset, max_relative = 1e-12);
            }
        }
    }

    #[test]
    fn li_sawamoto_packed_bed_without_a_packed_cell_is_cellwise() {
        // no cell reaches phi_max (a suspension, a dilute bed): nothing is packed
        let packed = MixingLength { bed: PackedBed::Packed, ..MixingLength::default() };
        let (z, dz) = uniform(50, 1e-3);
        let phi: Vec<f64> = (0..50).map(|i| 0.6 * (1.0 - i as f64 / 50.0)).collect();
        assert_eq!(lengths(&packed, &z, &dz, &phi), lengths(&MixingLength::default(), &z, &dz, &phi));
    }

    #[test]
    fn li_sawamoto_linear_profile_matches_integral() {
        // phi = phi_max (1 - z/H) over [0, H]: open fraction z/H, integral z^2/(2H); the
        // piecewise-constant integration is second order, exact up to O(dz^2).
        let m = MixingLength::default();
        let h = 0.1;
        let n = 400;
        let (z, dz) = uniform(n, h / n as f64);
        let phi: Vec<f64> = z.iter().map(|&zi| m.phi_max * (1.0 - zi / h)).collect();
        for (l, zi) in lengths(&m, &z, &dz, &phi).iter().zip(&z).skip(n / 10) {
            assert_relative_eq!(*l, 0.41 * zi * zi / (2.0 * h), max_relative = 1e-3);
        }
    }

    #[test]
    fn berzi_fraccarollo_floor_and_cap() {
        let m = with_form(MixingLengthForm::BerziFraccarollo);
        assert_relative_eq!(m.berzi_fraccarollo(0.0, D), 3.0 * D * 0.635f64.powi(3), max_relative = 1e-14);
        assert_eq!(m.berzi_fraccarollo(0.635, D), 0.2 * D);
        assert_eq!(m.berzi_fraccarollo(0.8, D), 0.2 * D);
        assert_eq!(m.berzi_fraccarollo(0.5, D), 0.2 * D); // 3 * 0.135^3 = 0.0074 < 0.2
        let (z, dz) = uniform(3, 1e-3);
        let l = lengths(&m, &z, &dz, &[0.0, 0.3, 0.6]);
        assert_eq!(l[0], m.berzi_fraccarollo(0.0, D));
        assert_eq!(l[1], (3.0 * D * 0.335f64.powf(3.0)).max(0.2 * D));
        assert_eq!(l[2], 0.2 * D);
    }

    #[test]
    fn validate_names_the_key() {
        let bad = MixingLength { kappa: 0.0, ..MixingLength::default() };
        assert_eq!(bad.validate().unwrap_err().key, "kappa");
        let bad = MixingLength { kappa: -0.4, ..MixingLength::default() };
        assert_eq!(bad.validate().unwrap_err().key, "kappa");
        let bad = MixingLength { phi_max: 1.0, ..MixingLength::default() };
        assert_eq!(bad.validate().unwrap_err().key, "phi_max");
        let bad = MixingLength { phi_max: 0.0, ..MixingLength::default() };
        assert_eq!(bad.validate().unwrap_err().key, "phi_max");
        let bad = MixingLength { floor: -0.1, ..MixingLength::default() };
        assert_eq!(bad.validate().unwrap_err().key, "floor");
        assert!(MixingLength { kappa: 1.0, ..MixingLength::default() }.validate().is_ok());
    }

    #[test]
    fn form_parses_from_lowercase_names_and_unknown_keys_are_refused() {
        let m: MixingLength = toml::from_str("form = \"berzi_fraccarollo\"\nexponent = 2").unwrap();
        assert_eq!(m.form, MixingLengthForm::BerziFraccarollo);
        assert_eq!(m.exponent, 2.0);
        assert_eq!(m.kappa, 0.41);
        let p: MixingLength = toml::from_str("form = \"prandtl\"").unwrap();
        assert_eq!(p.form, MixingLengthForm::Prandtl);
        assert!(toml::from_str::<MixingLength>("form = \"Prandtl\"").is_err());
        assert!(toml::from_str::<MixingLength>("kapa = 0.4").is_err());
        let b: MixingLength = toml::from_str("bed = \"packed\"").unwrap();
        assert_eq!(b.bed, PackedBed::Packed);
        assert_eq!(MixingLength::default().bed, PackedBed::Cellwise);
        assert!(toml::from_str::<MixingLength>("bed = \"Packed\"").is_err());
    }

    #[test]
    fn provides_eddy_viscosity_and_reynolds_stress() {
        let p = MixingLength::default().provides();
        assert!(p.contains(Field::EddyViscosity) && p.contains(Field::ReynoldsStress));
        assert!(!p.contains(Field::Tke));
    }

    proptest! {
        #[test]
        fn li_sawamoto_equals_prandtl_in_clear_fluid(n in 1usize..200, dz in 1e-5f64..1e-1) {
            let (z, dzs) = uniform(n, dz);
            let phi = vec![0.0; n];
            let ls = lengths(&MixingLength::default(), &z, &dzs, &phi);
            let pr = lengths(&with_form(MixingLengthForm::Prandtl), &z, &dzs, &phi);
            prop_assert_eq!(ls, pr);
        }

        #[test]
        fn li_sawamoto_monotone_and_bounded(
            cells in proptest::collection::vec((0.0f64..0.8, 1e-4f64..1e-2), 1..100),
        ) {
            let m = MixingLength::default();
            let dz: Vec<f64> = cells.iter().map(|c| c.1).collect();
            let phi: Vec<f64> = cells.iter().map(|c| c.0).collect();
            let mut face = 0.0;
            let z: Vec<f64> = dz.iter().map(|&d| { let c = face + 0.5 * d; face += d; c }).collect();
            let l = lengths(&m, &z, &dz, &phi);
            for w in l.windows(2) {
                prop_assert!(w[1] >= w[0]);
            }
            for (li, zi) in l.iter().zip(&z) {
                prop_assert!(*li >= 0.0 && *li <= 0.41 * zi * (1.0 + 1e-12));
            }
        }

        #[test]
        fn li_sawamoto_packed_equals_cellwise_on_a_bed_loosening_upwards(
            mut phi in proptest::collection::vec(0.0f64..0.8, 1..100),
            dz in 1e-4f64..1e-2,
        ) {
            // the packed top is the last cell at phi_max: below it every cell is packed
            // too, so both rules integrate the same open fractions
            phi.sort_by(|a, b| b.total_cmp(a));
            let (z, dzs) = uniform(phi.len(), dz);
            let packed = MixingLength { bed: PackedBed::Packed, ..MixingLength::default() };
            prop_assert_eq!(lengths(&packed, &z, &dzs, &phi), lengths(&MixingLength::default(), &z, &dzs, &phi));
        }

        #[test]
        fn li_sawamoto_packed_never_longer_than_cellwise(
            phi in proptest::collection::vec(0.0f64..0.8, 1..100),
            dz in 1e-4f64..1e-2,
        ) {
            let (z, dzs) = uniform(phi.len(), dz);
            let packed = MixingLength { bed: PackedBed::Packed, ..MixingLength::default() };
            let (lp, lc) = (lengths(&packed, &z, &dzs, &phi), lengths(&MixingLength::default(), &z, &dzs, &phi));
            for (p, c) in lp.iter().zip(&lc) {
                prop_assert!(*p >= 0.0 && *p <= *c);
            }
        }

        #[test]
        fn berzi_fraccarollo_between_floor_and_cap(phi in -0.1f64..1.0, d in 1e-5f64..1e-1) {
            let m = with_form(MixingLengthForm::BerziFraccarollo);
            let l = m.berzi_fraccarollo(phi.max(0.0), d);
            prop_assert!(l >= 0.2 * d);
            prop_assert!(l <= (3.0 * d * 0.635f64.powi(3)) * (1.0 + 1e-12));
        }

        #[test]
        fn eddy_viscosity_batch_is_l2_abs_dudz(
            cells in proptest::collection::vec((0.0f64..0.7, -100.0f64..100.0), 1..64),
            which in 0usize..3,
        ) {
            let form = [MixingLengthForm::Prandtl, MixingLengthForm::LiSawamoto, MixingLengthForm::BerziFraccarollo][which];
            let m = with_form(form);
            let n = cells.len();
            let (z, dz) = uniform(n, 1e-3);
            let phi: Vec<f64> = cells.iter().map(|c| c.0).collect();
            let dudz: Vec<f64> = cells.iter().map(|c| c.1).collect();
            let col = ColumnView { z: &z, dz: &dz, phi: &phi, dudz: &dudz, diameter: D, nu_f: 1e-6, transported: &[] };
            let mut l = vec![0.0; n];
            m.mixing_length(&col, &mut l);
            let mut nu = vec![0.0; n];
            m.eddy_viscosity(&col, &mut nu);
            for i in 0..n {
                prop_assert_eq!(nu[i], l[i] * l[i] * dudz[i].abs());
                prop_assert_eq!(nu[i], m.eddy_viscosity_point(l[i], dudz[i]));
            }
        }
    }
}
