//! The leap-frog rates `av` carries from one step to the next.

use crate::math::{Real, Sym3, Vector};

/// State of the leap-frog integration of `av` kept between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AvRates<const D: usize> {
    /// dv/dt.
    pub acc: Vector<D>,
    /// de/dt.
    pub de: Real,
    /// drho/dt.
    pub drho: Real,
    /// dS/dt.
    pub ds: Sym3,
    /// Equivalent strain rate, 1/s (rate-dependent strength).
    pub rate: Real,
    /// Half-step velocity (scratch).
    pub v_half: Vector<D>,
    /// Half-step energy (scratch).
    pub e_half: Real,
    /// Half-step density (scratch).
    pub rho_half: Real,
    /// Half-step deviator (scratch).
    pub s_half: Sym3,
    /// The rate of the hourglass displacement (effect `hourglass`), m/s.
    pub dhg: Vector<D>,
    /// Half-step hourglass displacement (scratch).
    pub hg_half: Vector<D>,
}

impl<const D: usize> Default for AvRates<D> {
    fn default() -> Self {
        AvRates {
            acc: Vector::<D>::zeros(),
            de: 0.0,
            drho: 0.0,
            ds: Sym3::ZERO,
            rate: 0.0,
            v_half: Vector::<D>::zeros(),
            e_half: 0.0,
            rho_half: 0.0,
            s_half: Sym3::ZERO,
            dhg: Vector::<D>::zeros(),
            hg_half: Vector::<D>::zeros(),
        }
    }
}

/// The reals of one particle's neighbour record ([`Workspace::rec`]) in `d`
/// dimensions: the fields of `RecordAt`, padded to whole groups of four (one AVX2 load
/// each).
///
/// [`Workspace::rec`]: crate::schemes::workspace::Workspace::rec
pub const fn record_len(d: usize) -> usize {
    RecordAt::of(d).end.div_ceil(4) * 4
}

/// Where each field of a neighbour record lies in `D` dimensions: what particle j gives
/// the pair loop of `av`, written once per rate evaluation by [`write_records`] so that
/// the loop reads one compact record per neighbour instead of a dozen arrays.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RecordAt {
    /// Position (D).
    pub x: usize,
    pub h: usize,
    /// Velocity (D).
    pub v: usize,
    pub rho: usize,
    pub cl: usize,
    /// `1/rho` (`Aux::inv_rho`; the volume is `m` times it, as `Aux::vol`).
    pub inv_rho: usize,
    pub m: usize,
    /// The `D x D` block of the pair's Cauchy stress (`cauchy`): [`sym_at`] of each
    /// component.
    pub sig: usize,
    /// The artificial-stress tensor, `D x D` row by row (zero without the effect).
    pub art: usize,
    /// The reals the fields take (the record is padded to whole groups of four).
    pub end: usize,
}

impl RecordAt {
    pub const fn of(d: usize) -> RecordAt {
        let sym = d * (d + 1) / 2;
        RecordAt {
            x: 0,
            h: d,
            v: d + 1,
            rho: 2 * d + 1,
            cl: 2 * d + 2,
            inv_rho: 2 * d + 3,
            m: 2 * d + 4,
            sig: 2 * d + 5,
            art: 2 * d + 5 + sym,
            end: 2 * d + 5 + sym + d * d,
        }
    }
}

/// The place of stress component `(a, b)` in a record's `D x D` block: the diagonal
/// first, then xy, xz, yz (Voigt's order).
#[inline(always)]
pub(crate) const fn sym_at(d: usize, a: usize, b: usize) -> usize {
    let (a, b) = if a <= b { (a, b) } else { (b, a) };
    if a == b {
        a
    } else {
        // (0, 1) -> d, (0, 2) -> d + 1, (1, 2) -> d + 2
        d + a + b - 1
    }
}
