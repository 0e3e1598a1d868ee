//! The EG arrays exactly as the EG paper prints them (Section 5 for n = 3 and 5, the Appendix
//! for n = 6..10), integers scaled by 10^5, rows r = 0, 1, ...; each row unfolds the 4 x 3 node
//! indices of one sector in the paper's order `00 10 20 30 01 11 21 31 02 12 22 32` (i fastest).
//!
//! The constants were generated from the paper's text; `tests/it/eg.rs` re-reads the verbatim
//! lines (`tests/data/eg-tables.txt`) and compares every integer. The Appendix lost all rows but
//! the first for n = 6..10 (see the papers README): those rows are kept for the record but give no
//! rules. Known extraction errors are listed in [`ERRATA`] and applied when the tables are
//! expanded into rules, never to the printed constants.

/// `A_{11}^3` as printed (2 rows, weights times 10^5).
pub const A11_3: [[i32; 12]; 2] = [
    [
        -1, -13, -37, 42, -13, 1671, 10243, 2049, -37, 10243, 50096, 5073,
    ],
    [0, 0, 38, 35, -4, 20, -169, -859, -77, -272, -1886, -2793],
];

/// `A_{22}^3` as printed (2 rows, weights times 10^5).
pub const A22_3: [[i32; 12]; 2] = [
    [0, 6, -49, -96, 6, -87, 2309, 1776, -49, 2309, 15760, 6979],
    [0, 0, 87, 57, -11, 39, -330, -1928, -58, -793, -3253, -5925],
];

/// `A_{21}^3` as printed (3 rows, weights times 10^5).
pub const A21_3: [[i32; 12]; 3] = [
    [0, -10, 2, 1, -5, 153, 8101, 7372, -173, 2036, 32183, 20229],
    [0, 3, 46, -11, -7, -3, 98, -966, -118, 328, 1736, -2329],
    [0, -8, -3, -128, 0, 16, -709, 307, 55, -198, -2703, 4434],
];

/// `A_{31}^3` as printed (3 rows, weights times 10^5).
pub const A31_3: [[i32; 12]; 3] = [
    [0, -3, 0, 76, 16, -125, 3642, 9873, 79, -370, 4902, 23927],
    [0, 16, 79, 79, -3, -125, -370, -1761, 0, 3642, 4902, -6789],
    [
        0, -7, 113, 79, -7, 80, -1088, -1761, 113, -1088, -6828, -6789,
    ],
];

/// `A_{32}^3` as printed (3 rows, weights times 10^5).
pub const A32_3: [[i32; 12]; 3] = [
    [0, -3, -30, 63, 9, -28, 792, 2658, 14, -402, 341, 7126],
    [0, 9, 14, 44, -3, -28, -402, -1866, -30, 792, 341, -6175],
    [0, -4, 63, 44, -4, 62, -1112, -1866, 63, -1112, -6536, -6175],
];

/// `A_{11}^5` as printed (3 rows, weights times 10^5).
pub const A11_5: [[i32; 12]; 3] = [
    [
        -129, 221, 50, -28, 221, 2629, 6368, 2877, 50, 6368, 61638, 6916,
    ],
    [-26, 68, -27, 2, 36, -65, -111, -16, 2, -177, -10, -388],
    [28, -41, -27, 21, -57, -73, 278, -17, 4, 306, -692, -676],
];

/// `A_{22}^5` as printed (3 rows, weights times 10^5).
pub const A22_5: [[i32; 12]; 3] = [
    [
        -491, 973, 57, -205, 973, -322, -4931, 1147, 57, -4931, 41825, 11869,
    ],
    [
        -74, 217, -103, 27, 68, -164, -225, -200, 76, -94, 2039, -3059,
    ],
    [
        165, -264, -112, 114, -332, -210, 1422, -150, 34, 1591, -5064, -3801,
    ],
];

/// `A_{21}^5` as printed (5 rows, weights times 10^5).
pub const A21_5: [[i32; 12]; 5] = [
    [
        -256, 482, 14, -132, 582, -379, 5085, 5035, 70, -3009, 48736, 23656,
    ],
    [
        -143, 317, -74, -16, 243, -143, -857, -44, -67, 434, 5702, -564,
    ],
    [
        89, -140, -48, 53, -195, -107, 773, -48, 67, 874, -2602, -1630,
    ],
    [
        57, -96, -42, 35, -83, -172, 625, -107, -74, 552, -1421, -2015,
    ],
    [
        49, -135, 104, -135, 59, -88, 456, 957, -37, 538, -1701, 3402,
    ],
];

/// `A_{31}^5` as printed (4 rows, weights times 10^5).
pub const A31_5: [[i32; 12]; 4] = [
    [
        -269, 492, -13, -197, 541, -115, -84, 9355, -192, -1203, 16754, 43563,
    ],
    [
        -269, 541, -192, -10, 492, -115, -1203, -313, -13, -84, 16754, 641,
    ],
    [
        103, -154, -54, 62, -243, -113, 944, -117, 118, 951, -2635, -2601,
    ],
    [
        79, -125, -80, 62, -125, -219, 800, -117, -80, 800, -2081, -2601,
    ],
];

/// `A_{32}^5` as printed (4 rows, weights times 10^5).
pub const A32_5: [[i32; 12]; 4] = [
    [
        -433, 772, -48, -208, 910, -235, -3106, 1327, -264, -2342, 12285, 25197,
    ],
    [
        -433, 910, -264, -41, 772, -235, -2342, -207, -48, -3106, 12285, -542,
    ],
    [
        220, -354, -73, 125, -509, -69, 1859, -299, 263, 1600, -6314, -5478,
    ],
    [
        169, -285, -124, 125, -285, -260, 1544, -299, -124, 1544, -5418, -5478,
    ],
];

/// `A_{11}^6` as printed (1 row, weights times 10^5).
pub const A11_6: [[i32; 12]; 1] = [[
    195, -490, 623, -140, -490, 4810, 4137, 3117, 623, 4137, 63933, 7100,
]];

/// `A_{22}^6` as printed (1 row, weights times 10^5).
pub const A22_6: [[i32; 12]; 1] = [[
    1107, -1155, 80, 540, -2274, 641, 1058, -2136, 1210, 1852, 1130, -54,
]];

/// `A_{21}^6` as printed (1 row, weights times 10^5).
pub const A21_6: [[i32; 12]; 1] = [[
    509, -852, 852, -6, -394, 421, 5574, 2189, 686, -3575, 49782, 25832,
]];

/// `A_{31}^6` as printed (1 row, weights times 10^5).
pub const A31_6: [[i32; 12]; 1] = [[
    508, -1059, 900, -93, -620, 727, 627, 5908, 110, 265, 14832, 49296,
]];

/// `A_{32}^6` as printed (1 row, weights times 10^5).
pub const A32_6: [[i32; 12]; 1] = [[
    781, -1843, 1572, -12, -773, 1255, -1663, -4879, 256, -1014, 9893, 34152,
]];

/// `A_{11}^7` as printed (1 row, weights times 10^5).
pub const A11_7: [[i32; 12]; 1] = [[
    1649, -2653, 1079, 712, -2653, 6369, 5384, 403, 1079, 5384, 62604, 8301,
]];

/// `A_{22}^7` as printed (1 row, weights times 10^5).
pub const A22_7: [[i32; 12]; 1] = [[
    2885, -4258, 990, 2256, -3619, 65, 11354, -5554, 1006, 1426, 45673, 29166,
]];

/// `A_{21}^7` as printed (1 row, weights times 10^5).
pub const A21_7: [[i32; 12]; 1] = [[
    1502, -2449, 429, 1395, -1616, -172, 3382, -5219, -161, 3370, -2822, 7200,
]];

/// `A_{31}^7` as printed (1 row, weights times 10^5).
pub const A31_7: [[i32; 12]; 1] = [[
    5498, -8345, 1585, 4853, -6921, 304, 10167, -22235, 490, 10813, -1236, 44864,
]];

/// `A_{32}^7` as printed (1 row, weights times 10^5).
pub const A32_7: [[i32; 12]; 1] = [[
    1937, -1799, -448, 449, -3428, -328, 4891, 278, 438, 8874, -1236, -4503,
]];

/// `A_{11}^8` as printed (1 row, weights times 10^5).
pub const A11_8: [[i32; 12]; 1] = [[
    2083, -2333, -209, 1181, -2807, -798, 4581, -3462, -29, 4678, -3918, 1918,
]];

/// `A_{22}^8` as printed (1 row, weights times 10^5).
pub const A22_8: [[i32; 12]; 1] = [[
    10373, -12886, 575, 8227, -12886, -3151, 16663, -25704, 575, 10663, 30076, 22718,
]];

/// `A_{21}^8` as printed (1 row, weights times 10^5).
pub const A21_8: [[i32; 12]; 1] = [[
    3675, -4738, 38, 3873, -4401, -1343, 8558, -5588, -532, 9748, 8074, 56324,
]];

/// `A_{31}^8` as printed (1 row, weights times 10^5).
pub const A31_8: [[i32; 12]; 1] = [[
    866, -784, -187, 16, -1374, -328, 2138, 330, -273, 2162, -130, -1074,
]];

/// `A_{32}^8` as printed (1 row, weights times 10^5).
pub const A32_8: [[i32; 12]; 1] = [[
    9036, -11741, -575, 10319, -10636, -3489, 20136, -34655, -909, 21657, -7903, 49585,
]];

/// `A_{11}^9` as printed (1 row, weights times 10^5).
pub const A11_9: [[i32; 12]; 1] = [[
    4093, -5443, 535, 2924, -5443, 6544, 9053, -3513, 535, 9053, 60551, 8408,
]];

/// `A_{22}^9` as printed (1 row, weights times 10^5).
pub const A22_9: [[i32; 12]; 1] = [[
    588, -430, -131, -642, -952, -318, 1665, 1930, -398, 1080, 381, -1623,
]];

/// `A_{21}^9` as printed (1 row, weights times 10^5).
pub const A21_9: [[i32; 12]; 1] = [[
    3781, -4394, -596, 4535, -4250, -2346, 8932, -6027, -1133, 10845, 8383, 56431,
]];

/// `A_{31}^9` as printed (1 row, weights times 10^5).
pub const A31_9: [[i32; 12]; 1] = [[
    9998, -11695, -2527, 13001, -11040, -6386, 23394, -37999, -2496, 25842, -8658, 49843,
]];

/// `A_{32}^9` as printed (1 row, weights times 10^5).
pub const A32_9: [[i32; 12]; 1] = [[
    2395, -2253, -396, -586, -3331, -1303, 6050, 1746, -821, 4129, 724, -1650,
]];

/// `A_{11}^10` as printed (1 row, weights times 10^5).
pub const A11_10: [[i32; 12]; 1] = [[
    4415, -5674, 258, 3428, -5674, 6674, 9056, -3686, 258, 9056, 60949, 7690,
]];

/// `A_{22}^10` as printed (1 row, weights times 10^5).
pub const A22_10: [[i32; 12]; 1] = [[
    8111, -8355, -2296, 5324, -9055, -6061, 19425, -13318, -3228, 19270, -6145, 7100,
]];

/// `A_{21}^10` as printed (1 row, weights times 10^5).
pub const A21_10: [[i32; 12]; 1] = [[
    1609, 1754, 463, -1732, 1664, 1228, -3620, 4479, 311, -3889, 1792, -2689,
]];

/// `A_{31}^10` as printed (1 row, weights times 10^5).
pub const A31_10: [[i32; 12]; 1] = [[
    9504, -10305, -3546, 13468, -9935, -7648, 22629, -36623, -3506, 25599, -6951, 48820,
]];

/// `A_{32}^10` as printed (1 row, weights times 10^5).
pub const A32_10: [[i32; 12]; 1] = [[
    3259, -3193, -783, 432, -3887, -2331, 8236, -1160, -1317, 5785, 504, 521,
]];

/// An extraction error in a printed array, found by computing the spectrum.
#[derive(Debug, Clone, Copy)]
pub struct Erratum {
    /// Valence.
    pub n: usize,
    /// Array (`"21"` for `A_21`).
    pub array: &'static str,
    /// Row (r).
    pub row: usize,
    /// Entry in the row (0..12, paper order).
    pub entry: usize,
    /// The printed value.
    pub printed: i32,
    /// The corrected value.
    pub corrected: i32,
    /// Why.
    pub reason: &'static str,
}

/// Known extraction errors of the printed arrays.
pub const ERRATA: [Erratum; 1] = [Erratum {
    n: 5,
    array: "21",
    row: 4,
    entry: 4,
    printed: 59,
    corrected: -59,
    reason: "A_21^5, row r = 4, weight of d_01: printed 59; with -59 the n = 5 rules give \
             lambda = 0.549995 and mu / lambda^2 = 1.000160 (published 1.00016), with 59 they give 1.0087",
}];

/// The printed arrays of valence `n`: `[A_11, A_22, A_21, A_31, A_32]` (as printed: complete for
/// n = 3 and 5, first rows only for 6..10), or `None` for other valences.
pub fn printed(n: usize) -> Option<[&'static [[i32; 12]]; 5]> {
    Some(match n {
        3 => [&A11_3, &A22_3, &A21_3, &A31_3, &A32_3],
        5 => [&A11_5, &A22_5, &A21_5, &A31_5, &A32_5],
        6 => [&A11_6, &A22_6, &A21_6, &A31_6, &A32_6],
        7 => [&A11_7, &A22_7, &A21_7, &A31_7, &A32_7],
        8 => [&A11_8, &A22_8, &A21_8, &A31_8, &A32_8],
        9 => [&A11_9, &A22_9, &A21_9, &A31_9, &A32_9],
        10 => [&A11_10, &A22_10, &A21_10, &A31_10, &A32_10],
        _ => return None,
    })
}

/// Valences whose published arrays are complete (the text lost the rest).
pub const COMPLETE_VALENCES: [usize; 2] = [3, 5];
