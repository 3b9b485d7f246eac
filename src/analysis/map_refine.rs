//! Adaptive refinement of an outcome map: which cells to compute next,
//! given the classes found so far, so that a map is computed coarse first
//! and then only where classes meet.
//!
//! The map is a grid of `nx × ny` cells (row-major, `index = j·nx + i`, the
//! order of [`grid_map`](super::outcome_map::grid_map)). Refinement works
//! on *sample lattices*: at stride s the lattice is every cell whose column
//! and row are multiples of s, plus the last column and row (so that the
//! map's edges are sampled at every level). Levels go from a coarse stride
//! s₀ (a power of two) down to 1, halving:
//! 1. Level s₀: every lattice cell is computed.
//! 2. Level s < s₀: each lattice cell of s that is not on the lattice of 2s
//!    looks at the cells of the 2s lattice around it: the corners of the
//!    2s-square (or 2s-segment) that contains it, widened by `halo` lattice
//!    lines on every side. If all of them are known and have the same
//!    class, the cell *inherits* that class without being computed;
//!    otherwise it is computed.
//! 3. After level 1 every cell has a class.
//!
//! So a uniform block is filled from its corners, and cells are computed
//! only within (1 + halo)·2s of where two classes were seen at the level
//! above. An island smaller than the coarse stride that touches no
//! lattice cell of the coarse level can be missed: that is the price of
//! not computing every cell, and `halo` ≥ 1 also catches boundaries that
//! bulge between two lattice lines.
//!
//! The scheme is pure (no threads, no physics): the caller computes the
//! cells each level asks for, in any order and on any number of threads,
//! and records their classes before asking for the next level. The
//! result depends only on the classes, never on the order they arrived in.

/// How a cell got its class.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// Not known yet.
    Unknown,
    /// Computed (asked for by [`Refiner::next_level`] and recorded).
    Computed,
    /// Filled from a uniform neighbourhood at the level above.
    Inherited,
}

/// The refinement state of one map (module docs).
#[derive(Clone, Debug)]
pub struct Refiner<C> {
    nx: usize,
    ny: usize,
    halo: usize,
    /// Stride of the coarsest level.
    coarse: usize,
    /// Stride of the level last handed out; `None` before the first.
    stride: Option<usize>,
    class: Vec<Option<C>>,
    source: Vec<Source>,
    finished: bool,
}

/// The lattice indices of stride `s` on an axis of `n` cells: multiples of
/// s below n, and n − 1.
fn lattice(n: usize, s: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..n).step_by(s).collect();
    if v.last() != Some(&(n - 1)) {
        v.push(n - 1);
    }
    v
}

/// The 2s-lattice indices around `i` (those of the segment containing it,
/// widened by `halo` on each side). `parent` is the 2s lattice, sorted.
fn around(parent: &[usize], i: usize, halo: usize) -> &[usize] {
    // The last lattice index ≤ i (parent[0] = 0 ≤ i always).
    let k = parent.partition_point(|&p| p <= i) - 1;
    let hi = if parent[k] == i { k } else { k + 1 };
    let lo = k.saturating_sub(halo);
    let hi = (hi + halo).min(parent.len() - 1);
    &parent[lo..=hi]
}

impl<C: Copy + PartialEq> Refiner<C> {
    /// A refiner for an `nx × ny` map whose coarse level has at least
    /// `coarse` cells along the longer axis (fewer only when the axis is
    /// shorter), with a `halo` of lattice lines (module docs; 1 is a good
    /// default).
    ///
    /// # Panics
    /// If `nx` or `ny` is 0 (a map has at least one cell).
    pub fn new(nx: usize, ny: usize, coarse: usize, halo: usize) -> Self {
        assert!(nx > 0 && ny > 0, "a map needs at least one cell");
        let n = nx.max(ny);
        // The largest power of two s with s·(coarse − 1) ≤ n − 1: the coarse
        // lattice then has at least `coarse` points along the longer axis.
        let mut s = 1;
        while 2 * s * (coarse.max(2) - 1) < n {
            s *= 2;
        }
        Self {
            nx,
            ny,
            halo,
            coarse: s,
            stride: None,
            class: vec![None; nx * ny],
            source: vec![Source::Unknown; nx * ny],
            finished: false,
        }
    }

    /// Width of the map, cells.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Height of the map, cells.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Stride of the coarse level.
    pub fn coarse_stride(&self) -> usize {
        self.coarse
    }

    /// Stride of the level last handed out by [`next_level`](Self::next_level)
    /// (`None` before the first call).
    pub fn stride(&self) -> Option<usize> {
        self.stride
    }

    /// Whether every level has been handed out and nothing is left.
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// The next level: fills the cells of its lattice that inherit their
    /// class, and returns the cells (indices, increasing) to compute and
    /// [`record`](Self::record) before the next call. `None` once the
    /// level of stride 1 has been handed out. A cell of the level above
    /// that was never recorded counts as a class of its own, so its
    /// neighbours are computed.
    pub(crate) fn next_level(&mut self) -> Option<Vec<usize>> {
        if self.finished {
            return None;
        }
        let s = match self.stride {
            None => self.coarse,
            Some(1) => {
                self.finished = true;
                return None;
            }
            Some(s) => s / 2,
        };
        self.stride = Some(s);
        let (xs, ys) = (lattice(self.nx, s), lattice(self.ny, s));
        let mut todo = Vec::new();
        if s == self.coarse {
            for &j in &ys {
                for &i in &xs {
                    todo.push(j * self.nx + i);
                }
            }
            return Some(todo);
        }
        let (px, py) = (lattice(self.nx, 2 * s), lattice(self.ny, 2 * s));
        let mut inherit = Vec::new();
        for &j in &ys {
            for &i in &xs {
                let c = j * self.nx + i;
                if self.source[c] != Source::Unknown {
                    continue;
                }
                match self.uniform(around(&px, i, self.halo), around(&py, j, self.halo)) {
                    Some(class) => inherit.push((c, class)),
                    None => todo.push(c),
                }
            }
        }
        for (c, class) in inherit {
            self.class[c] = Some(class);
            self.source[c] = Source::Inherited;
        }
        Some(todo)
    }

    /// The common class of the cells `xs × ys`, if all are known and equal.
    fn uniform(&self, xs: &[usize], ys: &[usize]) -> Option<C> {
        let mut common = None;
        for &j in ys {
            for &i in xs {
                let c = self.class[j * self.nx + i]?;
                match common {
                    None => common = Some(c),
                    Some(k) if k != c => return None,
                    Some(_) => {}
                }
            }
        }
        common
    }

    /// Records the computed class of cell `index`.
    pub fn record(&mut self, index: usize, class: C) {
        self.class[index] = Some(class);
        self.source[index] = Source::Computed;
    }

    /// The class of cell `index`, if computed or inherited.
    pub fn class(&self, index: usize) -> Option<C> {
        self.class[index]
    }

    /// How cell `index` got its class.
    pub fn source(&self, index: usize) -> Source {
        self.source[index]
    }

    /// Number of cells computed so far.
    pub fn computed(&self) -> usize {
        self.source.iter().filter(|&&s| s == Source::Computed).count()
    }

    /// Number of cells that inherited their class so far.
    pub fn inherited(&self) -> usize {
        self.source.iter().filter(|&&s| s == Source::Inherited).count()
    }

    /// The map as far as it is known, one entry per cell: each cell shows
    /// the class of the lattice cell that covers it at the finest level
    /// where that one is known (the cell itself once it is known). `None`
    /// only before anything covering it is known.
    pub fn picture(&self) -> Vec<Option<C>> {
        let mut out = Vec::with_capacity(self.nx * self.ny);
        let finest = self.stride.unwrap_or(self.coarse);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let mut s = finest;
                let mut shown = None;
                while s <= self.coarse {
                    let (ci, cj) = (i / s * s, j / s * s);
                    if let Some(c) = self.class[cj * self.nx + ci] {
                        shown = Some(c);
                        break;
                    }
                    s *= 2;
                }
                // The last row and column are lattice cells of their own.
                out.push(self.class[j * self.nx + i].or(shown));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs the refinement to the end with `f(i, j)` as the classifier;
    /// returns the refiner and, per level, its stride and computed cells.
    fn run<C: Copy + PartialEq>(
        nx: usize,
        ny: usize,
        coarse: usize,
        halo: usize,
        f: impl Fn(usize, usize) -> C,
    ) -> (Refiner<C>, Vec<(usize, Vec<usize>)>) {
        let mut r = Refiner::new(nx, ny, coarse, halo);
        let mut levels = Vec::new();
        while let Some(cells) = r.next_level() {
            for &c in &cells {
                assert_eq!(r.source(c), Source::Unknown, "cell {c} handed out twice");
                r.record(c, f(c % nx, c / nx));
            }
            levels.push((r.stride().unwrap(), cells));
        }
        (r, levels)
    }

    #[test]
    fn the_lattice_includes_the_last_index() {
        assert_eq!(lattice(10, 4), vec![0, 4, 8, 9]);
        assert_eq!(lattice(9, 4), vec![0, 4, 8]);
        assert_eq!(lattice(1, 8), vec![0]);
        let p = lattice(10, 4);
        assert_eq!(around(&p, 5, 0), &[4, 8]);
        assert_eq!(around(&p, 4, 0), &[4]);
        assert_eq!(around(&p, 5, 1), &[0, 4, 8, 9]);
        assert_eq!(around(&p, 9, 1), &[8, 9]);
    }

    #[test]
    fn the_coarse_level_has_about_the_asked_number_of_cells() {
        let r: Refiner<u8> = Refiner::new(128, 128, 16, 1);
        assert_eq!(r.coarse_stride(), 8);
        assert_eq!(lattice(128, 8).len(), 17);
        let r: Refiner<u8> = Refiner::new(256, 64, 16, 1);
        assert_eq!(r.coarse_stride(), 16);
        let r: Refiner<u8> = Refiner::new(5, 3, 16, 1);
        assert_eq!(
            r.coarse_stride(),
            1,
            "a map smaller than the coarse grid is computed whole"
        );
    }

    #[test]
    fn a_straight_boundary_refines_only_cells_along_it() {
        let (nx, ny, edge) = (128, 128, 50);
        let (r, levels) = run(nx, ny, 16, 1, |i, _| i >= edge);
        let (coarse, first) = &levels[0];
        assert_eq!(*coarse, 8);
        assert_eq!(first.len(), 17 * 17);
        for (s, cells) in &levels[1..] {
            // A cell is computed only if a 2s-lattice cell within
            // (1 + halo)·2s of it has the other class.
            let reach = 2 * 2 * s;
            for &c in cells {
                let i = c % nx;
                let d = if i >= edge { i - edge } else { edge - 1 - i };
                assert!(d < reach, "stride {s}: cell at column {i} is {d} from the boundary");
            }
        }
        let computed = r.computed();
        assert!(
            computed < nx * ny / 5,
            "{computed} of {} cells computed for one straight boundary",
            nx * ny
        );
        // …and the boundary itself is exact.
        for c in 0..nx * ny {
            assert_eq!(r.class(c), Some(c % nx >= edge));
        }
    }

    #[test]
    fn every_cell_gets_a_class_and_the_result_equals_the_full_grid() {
        // A disc, a diagonal band and a wedge: curved and straight
        // boundaries, four classes, features much larger than the coarse
        // stride.
        let f = |i: usize, j: usize| -> u8 {
            let (x, y) = (i as f64, j as f64);
            let disc = (x - 60.0).powi(2) + (y - 70.0).powi(2) < 30.0f64.powi(2);
            let band = (x + y - 150.0).abs() < 12.0;
            let wedge = y < 0.3 * x - 10.0;
            u8::from(disc) + 2 * u8::from(band) + 4 * u8::from(wedge)
        };
        for (nx, ny) in [(128, 128), (100, 37), (256, 64), (7, 5), (1, 1)] {
            let (r, _) = run(nx, ny, 16, 1, |i, j| f(i * 128 / nx, j * 128 / ny.max(1)));
            let want: Vec<Option<u8>> = (0..nx * ny)
                .map(|c| Some(f(c % nx * 128 / nx, c / nx * 128 / ny)))
                .collect();
            assert!(r.finished());
            assert_eq!(r.picture(), want, "{nx} × {ny}");
            for c in 0..nx * ny {
                assert_ne!(r.source(c), Source::Unknown, "{nx} × {ny}: cell {c}");
            }
            if nx * ny >= 128 * 64 {
                assert!(r.computed() < nx * ny / 2, "{nx} × {ny}: {} computed", r.computed());
            }
        }
    }

    #[test]
    fn the_picture_is_whole_after_the_coarse_level_and_a_uniform_map_stops_there() {
        let mut r: Refiner<u8> = Refiner::new(64, 64, 16, 1);
        assert!(r.picture().iter().all(Option::is_none));
        let cells = r.next_level().unwrap();
        for c in cells {
            r.record(c, 3);
        }
        assert!(
            r.picture().iter().all(|&c| c == Some(3)),
            "drawn whole from the coarse level"
        );
        let mut more = 0;
        while let Some(cells) = r.next_level() {
            more += cells.len();
        }
        assert_eq!(more, 0, "a uniform map is only sampled at the coarse level");
        assert_eq!(r.computed(), 17 * 17);
        assert!(r.finished());
        assert_eq!(r.next_level(), None);
    }

    #[test]
    fn a_cell_never_recorded_makes_its_neighbours_computed() {
        let mut r: Refiner<u8> = Refiner::new(32, 32, 4, 0);
        let cells = r.next_level().unwrap();
        let (&missing, rest) = cells.split_last().unwrap();
        for &c in rest {
            r.record(c, 1);
        }
        let next = r.next_level().unwrap();
        assert!(!next.is_empty());
        assert!(next.iter().all(|&c| r.source(c) == Source::Unknown));
        assert_eq!(r.class(missing), None);
    }
}
