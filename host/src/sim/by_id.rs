//! Errors that name particles by id: particles are renumbered in memory, so what the
//! core reports by memory index is mapped to the ids a user sees.

use gsph_core::neighbors::NeighborError;
use gsph_core::state::{check_finite_one, StepError, System};

/// A neighbour overflow naming the particle by its id (particles are renumbered in memory).
pub(super) fn overflow_by_id(e: NeighborError, ids: &[u32]) -> NeighborError {
    match e {
        NeighborError::Overflow {
            particle,
            found,
            capacity,
        } => NeighborError::Overflow {
            particle: ids[particle] as usize,
            found,
            capacity,
        },
        other => other,
    }
}

/// A step error naming the particle by its id; when several particles fail the finite
/// check, the one of lowest id (so the message does not depend on the memory order).
pub(super) fn cause_by_id<const D: usize>(
    cause: StepError,
    ids: &[u32],
    sys: &System<'_, D>,
) -> StepError {
    let bad = |i: usize| check_finite_one(sys, i).err();
    match cause {
        StepError::NonFinite { .. } | StepError::NonPositiveDensity { .. } => {
            let worst = (0..sys.len())
                .filter_map(|i| bad(i).map(|c| (ids[i], c)))
                .min_by_key(|(id, _)| *id);
            match worst {
                Some((id, StepError::NonFinite { field, .. })) => StepError::NonFinite {
                    particle: id as usize,
                    field,
                },
                Some((id, StepError::NonPositiveDensity { .. })) => StepError::NonPositiveDensity {
                    particle: id as usize,
                },
                // the core named a particle the finite check passes (a time step, say)
                _ => match cause {
                    StepError::NonFinite { particle, field } => StepError::NonFinite {
                        particle: ids[particle] as usize,
                        field,
                    },
                    StepError::NonPositiveDensity { particle } => StepError::NonPositiveDensity {
                        particle: ids[particle] as usize,
                    },
                    other => other,
                },
            }
        }
        other => other,
    }
}
