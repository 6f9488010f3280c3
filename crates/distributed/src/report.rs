//! What a distributed frame cost, per rank and in total, as rank 0 reports
//! it (plain data: no MPI here).

/// Per-rank figures of one frame, gathered on rank 0.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrameReport {
    pub ranks: usize,
    pub pixels: usize,
    pub rows: Vec<Row>,
}

/// One rank's figures (seconds, counts, bytes).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Row {
    pub trace_s: f64,
    pub fragments_sent: f64,
    pub fragments_received: f64,
    pub bytes_exchanged: f64,
    pub bytes_gathered: f64,
    /// Waiting at the barrier before the exchange (load imbalance).
    pub wait_s: f64,
    pub exchange_s: f64,
    pub sort_s: f64,
    pub blend_s: f64,
    pub gather_s: f64,
    pub segments: f64,
    pub tets: f64,
}

impl Row {
    pub const LEN: usize = 12;

    pub fn to_vec(self) -> Vec<f64> {
        vec![
            self.trace_s,
            self.fragments_sent,
            self.fragments_received,
            self.bytes_exchanged,
            self.bytes_gathered,
            self.wait_s,
            self.exchange_s,
            self.sort_s,
            self.blend_s,
            self.gather_s,
            self.segments,
            self.tets,
        ]
    }

    pub fn from_slice(v: &[f64]) -> Row {
        let at = |i: usize| v.get(i).copied().unwrap_or(0.0);
        Row {
            trace_s: at(0),
            fragments_sent: at(1),
            fragments_received: at(2),
            bytes_exchanged: at(3),
            bytes_gathered: at(4),
            wait_s: at(5),
            exchange_s: at(6),
            sort_s: at(7),
            blend_s: at(8),
            gather_s: at(9),
            segments: at(10),
            tets: at(11),
        }
    }
}

impl FrameReport {
    fn column<'a>(&'a self, f: impl Fn(&Row) -> f64 + 'a) -> impl Iterator<Item = f64> + 'a {
        self.rows.iter().map(f)
    }

    /// Largest value of a column over the ranks.
    pub fn max(&self, f: impl Fn(&Row) -> f64) -> f64 {
        self.column(f).fold(0.0, f64::max)
    }

    /// Mean of a column over the ranks.
    pub fn mean(&self, f: impl Fn(&Row) -> f64) -> f64 {
        self.sum(f) / self.rows.len().max(1) as f64
    }

    pub fn sum(&self, f: impl Fn(&Row) -> f64) -> f64 {
        self.column(f).sum()
    }

    /// Fragments per pixel of the image (all ranks').
    pub fn fragments_per_pixel(&self) -> f64 {
        self.sum(|r| r.fragments_sent) / self.pixels.max(1) as f64
    }

    /// Bytes that crossed between ranks: the exchange and the gather.
    pub fn bytes_total(&self) -> f64 {
        self.sum(|r| r.bytes_exchanged) + self.sum(|r| r.bytes_gathered)
    }

    /// The report in a few lines (times in ms, the slowest rank's: every
    /// stage ends in a collective, so the slowest sets the pace).
    pub fn describe(&self) -> String {
        let ms = |s: f64| s * 1e3;
        format!(
            "distributed over {} ranks: trace max {:.1} ms, mean {:.1} ms; {:.0} fragments \
             ({:.3} per pixel); {:.0} bytes exchanged, {:.0} bytes gathered; wait {:.2} ms, \
             exchange {:.2} ms, sort {:.2} ms, blend {:.2} ms, gather {:.2} ms (slowest rank \
             each)",
            self.ranks,
            ms(self.max(|r| r.trace_s)),
            ms(self.mean(|r| r.trace_s)),
            self.sum(|r| r.fragments_sent),
            self.fragments_per_pixel(),
            self.sum(|r| r.bytes_exchanged),
            self.sum(|r| r.bytes_gathered),
            ms(self.max(|r| r.wait_s)),
            ms(self.max(|r| r.exchange_s)),
            ms(self.max(|r| r.sort_s)),
            ms(self.max(|r| r.blend_s)),
            ms(self.max(|r| r.gather_s)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip_and_aggregate() {
        let a = Row {
            trace_s: 1.0,
            fragments_sent: 30.0,
            bytes_exchanged: 64.0,
            ..Row::default()
        };
        let b = Row {
            trace_s: 3.0,
            fragments_sent: 10.0,
            bytes_gathered: 16.0,
            ..Row::default()
        };
        assert_eq!(Row::from_slice(&a.to_vec()), a);
        assert_eq!(a.to_vec().len(), Row::LEN);
        let report = FrameReport {
            ranks: 2,
            pixels: 20,
            rows: vec![a, b],
        };
        assert_eq!(report.max(|r| r.trace_s), 3.0);
        assert_eq!(report.mean(|r| r.trace_s), 2.0);
        assert_eq!(report.fragments_per_pixel(), 2.0);
        assert_eq!(report.bytes_total(), 80.0);
        assert!(report.describe().contains("2 ranks"));
    }
}
