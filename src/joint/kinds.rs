//! Kinds of interfaces (distinct pairs of law and section), each with the return mapping's
//! constants prepared once.

use super::*;

/// What the return mapping of one law on one section computes before it looks at the jumps and
/// the history: the elastic stiffnesses D, the columns D m_j, the products a_i . D m_j, and the
/// factors of every active set's system (None where it is singular). A solver that maps many
/// joints of few kinds builds one per kind ([`Prepared::new`]) and passes it to
/// [`return_map`](super::return_map) as `MapOptions::prepared`: the same numbers, computed once.
#[derive(Debug, Clone)]
pub struct Prepared {
    pub(super) d: [f64; 3],
    pub(super) dm: [[f64; 3]; 4],
    pub(super) g_all: [[f64; 4]; 4],
    /// by active set (bit j: face j)
    pub(super) lu: [Option<Lu>; 16],
}

impl Prepared {
    /// The constants of `law` on `sec` (the faces' normals and flow do not depend on the
    /// strengths, which a history may soften).
    pub fn new(law: &JointLaw, sec: &Section) -> Self {
        let faces = Faces::new(law, sec, 0.0, 0.0);
        let d = stiffness(law, sec);
        let dm = flow_columns(&faces, &d);
        let g_all = face_products(&faces, &dm);
        let mut lu = [None; 16];
        for (mask, lu) in lu.iter_mut().enumerate().skip(1) {
            let mask = mask as u8;
            if mask.count_ones() <= 3 {
                let (act, n) = faces_of(mask);
                let mut g = set_matrix(&g_all, &act[..n]);
                *lu = factor_small(&mut g, n);
            }
        }
        Prepared { d, dm, g_all, lu }
    }
}

/// The kinds of many joints: the distinct pairs of law and section, each with its
/// [`Prepared`] constants, and the kind of each joint. A wall of equal blocks has a handful of
/// kinds however many joints it has.
#[derive(Debug, Clone, Default)]
pub(crate) struct Kinds {
    pub(super) table: Vec<(Section, Prepared)>,
    pub(super) of: Vec<u16>,
}

impl Kinds {
    /// The kind of a joint whose pair did not fit in the table: mapped without prepared
    /// constants (the same numbers, computed per mapping).
    pub const NONE: u16 = u16::MAX;

    /// The solvers' size of the table: 256 kinds, 0.7 MB at most.
    pub const MAX: usize = 256;

    /// The kinds of `joints`, each given as (an identifier of its law, the law, its section):
    /// equal identifiers must mean equal laws, sections are compared bit for bit. At most `max`
    /// kinds (each 2.6 kB) are kept, at most 65,535.
    pub fn new<'a>(joints: impl IntoIterator<Item = (u8, &'a JointLaw, &'a Section)>, max: usize) -> Self {
        let max = max.min(Self::NONE as usize);
        let (mut table, mut of, mut index) = (vec![], vec![], std::collections::HashMap::new());
        for (id, law, sec) in joints {
            let key = (id, [sec.area.to_bits(), sec.inertia.to_bits(), sec.length.to_bits()]);
            of.push(match index.get(&key) {
                Some(&i) => i,
                None if table.len() < max => {
                    table.push((*sec, Prepared::new(law, sec)));
                    index.insert(key, (table.len() - 1) as u16);
                    (table.len() - 1) as u16
                }
                None => Self::NONE,
            });
        }
        Kinds { table, of }
    }

    /// The kind of joint `k` ([`Kinds::NONE`] if not in the table).
    pub fn kind(&self, k: usize) -> u16 {
        self.of[k]
    }

    /// The section and constants of a kind, if it is in the table.
    pub fn get(&self, kind: u16) -> Option<&(Section, Prepared)> {
        self.table.get(kind as usize)
    }

    /// The prepared constants of joint `k`, if its kind is in the table.
    pub fn prepared(&self, k: usize) -> Option<&Prepared> {
        self.get(self.of[k]).map(|(_, p)| p)
    }

    /// The number of kinds in the table.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.table.len()
    }

}
