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

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use saltus_core::Error;

use super::drag::FluidField;
use super::particles::Particles;

/// Name of the collection file in the snapshot folder.
pub const COLLECTION: &str = "series.pvd";

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

/// The snapshot series of one run: its folder and the snapshots written so far. A DEM
/// checkpoint saves the snapshots written (not the folder), so that the collection of a
/// restarted run lists them all.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct Series {
    #[serde(skip)]
    dir: PathBuf,
    /// (time, file, part) of every dataset written
    entries: Vec<(f64, String, u8)>,
    count: usize,
}

impl Series {
    /// A series written into `dir` (created at the first snapshot).
    pub fn new(dir: &Path) -> Self {
        Self { dir: dir.to_path_buf(), entries: Vec::new(), count: 0 }
    }

    /// The same series, written on into `dir` (after a restart).
    pub fn moved_to(mut self, dir: &Path) -> Self {
        self.dir = dir.to_path_buf();
        self
    }

    /// Snapshots written so far.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether no snapshot was written.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Write the snapshot of simulated time `time` (s): the particles, the column when
    /// given, and the collection updated.
    pub fn write(&mut self, time: f64, p: &Particles, column: Option<&FluidField>) -> Result<(), Error> {
        let refuse = |what: &str, array: String| {
            Error::Invalid(format!(
                "{}: snapshot at t = {time:e} s not written: {what} array `{array}` holds a non-finite value",
                self.dir.display()
            ))
        };
        if !time.is_finite() {
            return Err(refuse("the", "time".into()));
        }
        let mut files =
            vec![(format!("particles_{:05}.vtp", self.count), particles_vtp(p).map_err(|a| refuse("particle", a))?)];
        if let Some(f) = column {
            files.push((format!("column_{:05}.vtp", self.count), column_vtp(f).map_err(|a| refuse("column", a))?));
        }
        std::fs::create_dir_all(&self.dir).map_err(|source| Error::Io { file: self.dir.clone(), source })?;
        for (part, (name, text)) in files.into_iter().enumerate() {
            let f = self.dir.join(&name);
            std::fs::write(&f, text).map_err(|source| Error::Io { file: f, source })?;
            self.entries.push((time, name, part as u8));
        }
        self.count += 1;
        let f = self.dir.join(COLLECTION);
        std::fs::write(&f, self.collection()).map_err(|source| Error::Io { file: f, source })
    }

    /// The `.pvd` text of the snapshots written so far.
    pub fn collection(&self) -> String {
        let mut s = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<Collection>\n",
        );
        for (t, file, part) in &self.entries {
            // {:e} prints the shortest text that reads back as the same f64
            let _ = writeln!(s, "<DataSet timestep=\"{t:e}\" group=\"\" part=\"{part}\" file=\"{file}\"/>");
        }
        s.push_str("</Collection>\n</VTKFile>\n");
        s
    }
}

impl super::solver::Lagrangian<'_> {
    /// Write ParaView snapshots ([`self`](super::vtk)) into `dir` every
    /// `solver.lagrangian.vtk_period` of flow time (if > 0).
    pub fn set_vtk_dir(&mut self, dir: &Path) {
        if self.cfg.settings.numerics.vtk_period > 0.0 {
            // a restored run goes on with the snapshots its checkpoint lists
            self.vtk = Some(match self.vtk.take() {
                Some(series) => series.moved_to(dir),
                None => Series::new(dir),
            });
        }
    }

    /// The snapshot series, when snapshots are written.
    pub fn vtk_series(&self) -> Option<&Series> {
        self.vtk.as_ref()
    }

    /// Why a snapshot was not written (the first failure), if one was not.
    pub fn vtk_error(&self) -> Option<&str> {
        self.vtk_error.as_deref()
    }

    /// Write the snapshot of the present state; a failure is kept for the report.
    pub(super) fn write_vtk(&mut self) {
        let column = (self.cfg.settings.numerics.fluid != saltus_core::scene::FluidMode::Off).then_some(&self.field);
        if let Some(series) = self.vtk.as_mut() {
            // a failed snapshot does not stop the run (the report tells it); the summary
            // still tells the result
            if let Err(e) = series.write(self.time, &self.dem.p, column) {
                self.vtk_error.get_or_insert_with(|| e.to_string());
            }
        }
    }
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
