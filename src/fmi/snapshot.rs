//! FMU states (fmi2GetFMUstate & co): a boxed snapshot of the simulation plus the adapter's
//! own state-machine state and time bookkeeping, and its byte serialization.

use super::machine::Machine;
use crate::simulation::Simulation;

/// The adapter's time bookkeeping.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    /// Start time from fmi2SetupExperiment (0 by default).
    pub start: f64,
    /// Stop time from fmi2SetupExperiment, if defined.
    pub stop: Option<f64>,
    /// The current communication point (last successful time).
    pub time: f64,
}

impl Clock {
    pub const NEW: Clock = Clock {
        start: 0.0,
        stop: None,
        time: 0.0,
    };
}

/// What an `fmi2FMUstate` handle points to.
pub struct Snapshot {
    pub sim: Simulation,
    pub machine: Machine,
    pub clock: Clock,
    /// Serialized bytes, computed on demand by fmi2SerializedFMUstateSize and reused by
    /// fmi2SerializeFMUstate (a snapshot never changes once taken, except by being
    /// overwritten, which clears this).
    pub serialized: Option<Vec<u8>>,
}

const MAGIC: &[u8; 8] = b"TRBFMU01";
const HEADER: usize = 8 + 1 + 8 + 1 + 8 + 8;

impl Snapshot {
    pub fn bytes(&mut self) -> &[u8] {
        if self.serialized.is_none() {
            let mut out = Vec::new();
            out.extend_from_slice(MAGIC);
            out.push(self.machine.to_byte());
            out.extend_from_slice(&self.clock.start.to_le_bytes());
            out.push(self.clock.stop.is_some() as u8);
            out.extend_from_slice(&self.clock.stop.unwrap_or(0.0).to_le_bytes());
            out.extend_from_slice(&self.clock.time.to_le_bytes());
            out.extend_from_slice(&self.sim.serialize_state());
            self.serialized = Some(out);
        }
        self.serialized.as_deref().expect("just serialized")
    }

    /// Rebuild a snapshot from `bytes`, using `template` (the instance's simulation, same
    /// bearing) for everything that is not serialized.
    pub fn from_bytes(template: &Simulation, bytes: &[u8]) -> Result<Snapshot, String> {
        if bytes.len() < HEADER || &bytes[..8] != MAGIC {
            return Err("not a serialized FMU state of TaperedRollerBearing (bad header)".into());
        }
        let f64_at = |i: usize| f64::from_le_bytes(bytes[i..i + 8].try_into().expect("8 bytes"));
        let machine = Machine::from_byte(bytes[8])
            .ok_or_else(|| format!("corrupt serialized FMU state: unknown state-machine state {}", bytes[8]))?;
        let start = f64_at(9);
        let stop = match bytes[17] {
            0 => None,
            1 => Some(f64_at(18)),
            b => return Err(format!("corrupt serialized FMU state: bad stop-time flag {b}")),
        };
        let time = f64_at(26);
        let mut sim = template.clone();
        sim.deserialize_state(&bytes[HEADER..])?;
        Ok(Snapshot {
            sim,
            machine,
            clock: Clock { start, stop, time },
            serialized: None,
        })
    }
}
