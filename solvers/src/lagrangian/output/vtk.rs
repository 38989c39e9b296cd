//! Snapshots for ParaView: binary VTK XML PolyData (`.vtp`) and one `.pvd` collection
//! carrying the simulated times.
//!
//! Layout of the folder (`<out>/vtk/`), one snapshot `NNNNN` every
//! `solver.lagrangian.vtk_period` of flow time:
//!
//! - `particles_NNNNN.vtp`: every particle as a vertex, with the point data `radius` and
//!   `diameter` (m), `velocity` and `angular_velocity` (3-vectors), `id` (index in the
//!   particle arrays) and `fixed` (1 for a particle of the rough layer, 0 for a mobile one);
//! - `column_NNNNN.vtp`: the fluid column as a polyline along z at x = y = 0 (one point
//!   per cell centre, in the particles' coordinates, so it overlays the bed), with the
//!   point data `u_f`, `phi`, `nu_t`, and `k`, `omega` when the turbulence closure
//!   transports them; absent when the fluid is off;
//! - `series.pvd`: the collection; each snapshot is one `timestep` (the flow time in
//!   seconds) with the particles as `part="0"` and the column as `part="1"`. It is
//!   rewritten after every snapshot, so an interrupted run leaves a readable series.
//!
//! A polyline rather than a rectilinear grid: a 1D column is a line of points, and one
//! PolyData type for both datasets lets ParaView read the collection as one multiblock.
//!
//! Arrays are `format="binary"`: base64 of a little-endian `UInt64` byte count followed
//! by the little-endian values (the VTK XML encoding with `header_type="UInt64"`), which
//! ParaView and VTK's `vtkXMLPolyDataReader` read. Every number written is finite: a
//! snapshot is taken right after the state check of a fluid update, and a snapshot
//! holding a non-finite value is refused rather than written.

use crate::lagrangian::coupling::drag::FluidField;
use crate::lagrangian::engine::particles::Particles;
use std::fmt::Write as _;

/// Name of the collection file in the snapshot folder.
pub use crate::run::paraview::COLLECTION;

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Standard base64 (with padding) of `bytes`, appended to `out`.
fn base64(bytes: &[u8], out: &mut String) {
    for c in bytes.chunks(3) {
        let b = [c[0], c.get(1).copied().unwrap_or(0), c.get(2).copied().unwrap_or(0)];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= c.len() {
                out.push(B64[((v >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
}

/// A numeric VTK array type.
trait Scalar: Copy {
    const NAME: &'static str;
    fn put(self, out: &mut Vec<u8>);
    fn finite(self) -> bool;
}

impl Scalar for f64 {
    const NAME: &'static str = "Float64";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn finite(self) -> bool {
        self.is_finite()
    }
}

impl Scalar for i64 {
    const NAME: &'static str = "Int64";
    fn put(self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn finite(self) -> bool {
        true
    }
}

impl Scalar for u8 {
    const NAME: &'static str = "UInt8";
    fn put(self, out: &mut Vec<u8>) {
        out.push(self);
    }
    fn finite(self) -> bool {
        true
    }
}

/// One `<DataArray>` element, binary encoded; `Err(name)` when a value is not finite.
fn array<T: Scalar>(
    s: &mut String,
    buf: &mut Vec<u8>,
    name: &str,
    components: usize,
    values: impl Iterator<Item = T>,
) -> Result<(), String> {
    buf.clear();
    buf.extend_from_slice(&[0; 8]);
    for v in values {
        if !v.finite() {
            return Err(name.to_string());
        }
        v.put(buf);
    }
    let len = (buf.len() - 8) as u64;
    buf[..8].copy_from_slice(&len.to_le_bytes());
    let _ = write!(
        s,
        "<DataArray type=\"{}\" Name=\"{name}\" NumberOfComponents=\"{components}\" format=\"binary\">",
        T::NAME
    );
    base64(buf, s);
    s.push_str("</DataArray>\n");
    Ok(())
}

fn header(s: &mut String, points: usize, verts: usize, lines: usize) {
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<PolyData>\n",
    );
    let _ = writeln!(
        s,
        "<Piece NumberOfPoints=\"{points}\" NumberOfVerts=\"{verts}\" NumberOfLines=\"{lines}\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
    );
}

const FOOTER: &str = "</Piece>\n</PolyData>\n</VTKFile>\n";

/// Interleaved 3-vectors of three component slices.
fn vec3<'a>(a: &'a [f64], b: &'a [f64], c: &'a [f64]) -> impl Iterator<Item = f64> + 'a {
    a.iter().zip(b).zip(c).flat_map(|((&x, &y), &z)| [x, y, z])
}

/// The particles as a `.vtp` document; `Err(array)` when one of its values is not finite.
pub fn particles_vtp(p: &Particles) -> Result<String, String> {
    let n = p.len();
    let mut s = String::with_capacity(n * 120 + 2048);
    let mut buf = Vec::with_capacity(n * 24 + 8);
    header(&mut s, n, n, 0);
    s.push_str("<PointData Scalars=\"diameter\" Vectors=\"velocity\">\n");
    array(&mut s, &mut buf, "radius", 1, p.radius.iter().copied())?;
    array(&mut s, &mut buf, "diameter", 1, p.radius.iter().map(|r| 2.0 * r))?;
    array(&mut s, &mut buf, "velocity", 3, vec3(&p.vx, &p.vy, &p.vz))?;
    array(&mut s, &mut buf, "angular_velocity", 3, vec3(&p.wx, &p.wy, &p.wz))?;
    array(&mut s, &mut buf, "id", 1, (0..n).map(|k| k as i64))?;
    array(&mut s, &mut buf, "fixed", 1, (0..n).map(|k| u8::from(k >= p.n_mobile)))?;
    s.push_str("</PointData>\n<Points>\n");
    array(&mut s, &mut buf, "Points", 3, vec3(&p.x, &p.y, &p.z))?;
    s.push_str("</Points>\n<Verts>\n");
    array(&mut s, &mut buf, "connectivity", 1, (0..n).map(|k| k as i64))?;
    array(&mut s, &mut buf, "offsets", 1, (1..=n).map(|k| k as i64))?;
    s.push_str("</Verts>\n");
    s.push_str(FOOTER);
    Ok(s)
}

/// The fluid column as a `.vtp` polyline along z at x = y = 0; `Err(array)` when one of
/// its values is not finite.
pub fn column_vtp(field: &FluidField) -> Result<String, String> {
    let n = field.u.len();
    let mut s = String::with_capacity(n * 80 + 2048);
    let mut buf = Vec::with_capacity(n * 24 + 8);
    header(&mut s, n, 0, 1);
    s.push_str("<PointData Scalars=\"u_f\">\n");
    array(&mut s, &mut buf, "u_f", 1, field.u.iter().copied())?;
    array(&mut s, &mut buf, "phi", 1, field.phi.iter().copied())?;
    array(&mut s, &mut buf, "nu_t", 1, field.nu_t.iter().copied())?;
    let [k, omega] = &field.k_omega;
    if k.len() == n && omega.len() == n {
        array(&mut s, &mut buf, "k", 1, k.iter().copied())?;
        array(&mut s, &mut buf, "omega", 1, omega.iter().copied())?;
    }
    s.push_str("</PointData>\n<Points>\n");
    let z = |c: usize| field.base + (c as f64 + 0.5) * field.dz;
    array(&mut s, &mut buf, "Points", 3, (0..n).flat_map(|c| [0.0, 0.0, z(c)]))?;
    s.push_str("</Points>\n<Lines>\n");
    array(&mut s, &mut buf, "connectivity", 1, (0..n).map(|k| k as i64))?;
    array(&mut s, &mut buf, "offsets", 1, std::iter::once(n as i64))?;
    s.push_str("</Lines>\n");
    s.push_str(FOOTER);
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(text: &str) -> Vec<u8> {
        let val = |c: u8| B64.iter().position(|&b| b == c).unwrap() as u32;
        let bytes: Vec<u8> = text.bytes().filter(|&c| c != b'=').collect();
        let mut out = Vec::new();
        for c in bytes.chunks(4) {
            let v = c.iter().enumerate().fold(0u32, |a, (k, &b)| a | (val(b) << (18 - 6 * k)));
            out.extend(v.to_be_bytes()[1..c.len()].iter().copied());
        }
        out
    }

    #[test]
    fn base64_matches_the_standard_alphabet() {
        for (raw, enc) in [("", ""), ("f", "Zg=="), ("fo", "Zm8="), ("foo", "Zm9v"), ("foobar", "Zm9vYmFy")] {
            let mut s = String::new();
            base64(raw.as_bytes(), &mut s);
            assert_eq!(s, enc);
            assert_eq!(decode(&s), raw.as_bytes());
        }
    }

    #[test]
    fn particles_read_back() {
        let mut p = Particles::default();
        p.push([0.0, 1.0, 2.0], [0.5, 0.0, 0.0], [0.0; 3], 0.003, 2500.0, false);
        p.push([1.0, 1.0, 0.0], [0.0; 3], [0.0; 3], 0.003, 2500.0, true);
        let s = particles_vtp(&p).unwrap();
        assert!(s.contains("NumberOfPoints=\"2\" NumberOfVerts=\"2\""));
        let points = s.split("Name=\"Points\"").nth(1).unwrap();
        let data = &points[points.find('>').unwrap() + 1..points.find('<').unwrap()];
        let bytes = decode(data);
        assert_eq!(u64::from_le_bytes(bytes[..8].try_into().unwrap()), 48);
        let xyz: Vec<f64> = bytes[8..].chunks(8).map(|c| f64::from_le_bytes(c.try_into().unwrap())).collect();
        assert_eq!(xyz, [0.0, 1.0, 2.0, 1.0, 1.0, 0.0]);
        p.vx[1] = f64::NAN;
        assert_eq!(particles_vtp(&p).unwrap_err(), "velocity");
    }
}
