//! The GPU kernel's exit table, derived from the faces' vertex order
//! (the CPU walk decides its exits in `face.rs`; the kernel looks them up).

use tetray_mesh::FACE_VERTICES;

/// The GPU kernel's exit table, in the tetrahedron's local numbering (the
/// CPU walk keeps the entry face in the ray's own cyclic order instead:
/// [`crate::face`]). For apex `a` (the vertex opposite the entry face): its
/// three other vertices in increasing order, and for each pattern of the signs of the
/// edges apex -> k (bit `i` set when the edge to the `i`-th of them is
/// positive) the exit face with the vertices following and preceding the
/// apex in that face's counter-clockwise order, or `None` (all signs equal:
/// only possible in a degenerate tetrahedron).
struct ApexTable {
    others: [usize; 3],
    exits: [Option<(usize, usize, usize)>; 8],
}

const APEX_TABLES: [ApexTable; 4] = apex_tables();

/// The exit table packed as the GPU kernel stores it: for apex `a` and sign
/// code `c`, `face | next << 4 | prev << 8`, or `0xffff` for none.
pub fn packed_exit_table() -> [[u32; 8]; 4] {
    std::array::from_fn(|apex| {
        std::array::from_fn(|code| match APEX_TABLES[apex].exits[code] {
            Some((f, next, prev)) => (f | next << 4 | prev << 8) as u32,
            None => 0xffff,
        })
    })
}

/// The exit face has all three edge signs positive. Its edge on the entry
/// face is already positive (adjacent faces run a shared edge in opposite
/// directions, signs are antisymmetric, and every entry face is all
/// negative), so face `f` is the exit exactly when the edge apex -> next is
/// positive and apex -> prev negative: three edge signs decide the exit.
const fn apex_tables() -> [ApexTable; 4] {
    let mut tables = [
        ApexTable {
            others: [1, 2, 3],
            exits: [None; 8],
        },
        ApexTable {
            others: [0, 2, 3],
            exits: [None; 8],
        },
        ApexTable {
            others: [0, 1, 3],
            exits: [None; 8],
        },
        ApexTable {
            others: [0, 1, 2],
            exits: [None; 8],
        },
    ];
    let mut apex = 0;
    while apex < 4 {
        let others = tables[apex].others;
        let mut code = 0;
        while code < 8 {
            let mut f = 0;
            while f < 4 {
                if f != apex {
                    let v = FACE_VERTICES[f];
                    let mut i = 0;
                    while v[i] != apex {
                        i += 1;
                    }
                    let (next, prev) = (v[(i + 1) % 3], v[(i + 2) % 3]);
                    if bit_of(others, code, next) && !bit_of(others, code, prev) {
                        tables[apex].exits[code] = Some((f, next, prev));
                    }
                }
                f += 1;
            }
            code += 1;
        }
        apex += 1;
    }
    tables
}

/// Whether `code` marks the edge to vertex `k` (one of `others`) positive.
const fn bit_of(others: [usize; 3], code: usize, k: usize) -> bool {
    let mut i = 0;
    while others[i] != k {
        i += 1;
    }
    code & (1 << i) != 0
}
