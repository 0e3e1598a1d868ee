//! G^1 caps: close the hole inside the last ring of a patch complex with `n` tensor-product
//! patches that join the ring C^1 and each other G^1, centred at a given point with a given
//! tangent plane, for every scheme that writes patches.
//!
//! The hole is described scheme-independently by [`Hole`] (conventions: [`hole`]); the cap is
//! one fixed linear map of the hole's data vector ([`Hole::data`]) per (valence, layout, segment
//! degrees, cap degree, centre condition), [`CapMap`], built once and cached ([`cap_map`]); its
//! [`CapMap::matrix`] is what a stencil table composes with the ring's own stencils.
//!
//! # Conditions
//!
//! Sector `s` is one bi-`d` patch `P_s` (quad layout; a triangle hole is first turned into
//! kites, [`Hole::to_quad_layout`]). All conditions are linear, scalar and the same for x, y, z:
//!
//! * **C^1 to the ring**: the two outer layers of coefficients along each outer side are the
//!   segment's boundary curve and boundary + cross / d (degree-raised). They are set exactly
//!   (eliminated before the solve), so value and first cross derivative match the data to
//!   rounding, with the parameter speed of the data.
//! * **centre and tangent plane**: `b_00 = C`, `b_10 = C + t_s / d`, `b_01 = C + t_(s+1) / d`
//!   with `t_s = cos(2 pi s / n) T0 + sin(2 pi s / n) T1`: every patch's normal at the centre is
//!   `T0 x T1`, so the cap is G^1 at the centre and the first-order vertex-enclosure condition
//!   `t_(s+1) + t_(s-1) = 2 cos(2 pi / n) t_s` holds by construction.
//! * **C^0 and G^1 across spoke `s`** (`P_s(u, 0) = P_(s-1)(0, u)`): the standard relation with
//!   scalar weights `a = b = 1`, `c = -w`:
//!   `d_v P_s(u, 0) + d_u P_(s-1)(0, u) = w(u) d_u P_s(u, 0)`,
//!   `w(u) = 2 cos(2 pi / n) (1 - u)^2 + kappa u (1 - u)`, imposed as a polynomial identity of
//!   degree `d + 1` (all its Bernstein coefficients). Since both weights of the cross
//!   derivatives are 1 > 0 the normals agree in orientation, not only in direction.
//!   `w(0) = 2 cos(2 pi / n)` is forced by the centre; `w(1) = 0` makes the relation the plain
//!   C^1 join of the ring's chart at the spoke end, and `w'(1) = -kappa` is forced by the ring:
//!   for a tensor-grid ring at the spoke end (Catmull-Clark, EG, QAS+, guided, Doo-Sabin, PGS,
//!   TPS) the two cap pieces beside a spoke end are two unit squares of one affine chart, whose
//!   twists cancel: `kappa = 0`; for kites on a three-direction lattice (Loop) the bilinear kite
//!   maps' twists add up to `-(M_s - C)` in the chart, the spoke direction: `kappa = 1` (the
//!   regular `n = 6` fan has exactly `w = 1 - u`). A quadratic `w` is the lowest degree meeting
//!   these three conditions.
//! * **centre jet** ([`Centre::QuadraticJet`]): all patches share one quadratic
//!   expansion at the centre, `P_s = q o phi_s + O(3)` with planar 2-jets
//!   `phi_s = u e_s + v e_(s+1) + k u v (e_s + e_(s+1))`, `k = w'(0) / (2 (1 + cos(2 pi / n)))`
//!   (the symmetric solution of the relation's derivative at the centre for the planar map) and
//!   the Hessian of `q` (three vectors) free. This is the second-order vertex-enclosure
//!   condition made explicit: for even `n` the relation's derivative at the centre is a circulant
//!   system `tau_s + tau_(s-1) = rhs_s` (twists `tau_s`) that is singular and needs
//!   `sum (-1)^s rhs_s = 0`, i.e. `sum (-1)^s d_uu P_s(0, 0) = 0` for `n != 4`; a common
//!   quadratic satisfies it identically. The cap is then curvature continuous at the centre
//!   (like the guided cap of Appendix B). [`Centre::TangentPlane`] leaves the second
//!   derivatives to the solve (the enclosure condition is then one of the solved rows). The
//!   default, [`Centre::Auto`], takes the lowest degree certified for the tangent plane and adds
//!   the jet where that degree allows it: bi-3 / bi-4 caps keep the plane (`n = 4`, odd `n`),
//!   the bi-5 caps of even `n` and all bi-4 caps of `n = 3` get the jet. On the real rings the
//!   jet removes spurious sign changes of the Gauss curvature at equal degree (Catmull-Clark,
//!   saddle, `n = 6`: cap `K` in `[-0.73, -0.11]` with the jet, `[-0.73, -0.011]` without), and
//!   the bi-4 plane caps of odd `n` are as fair as bi-5 jet caps (QAS+, convex, `n = 7`:
//!   `[0.097, 0.125]` against `[0.065, 0.127]`, the ring `[0.086, 0.125]`).
//!
//! # Free parameters and how they are fixed
//!
//! What the conditions leave ([`CapMap::free_parameters`], per coordinate) is fixed by minimising
//! the sum over the cap patches of the fairness functional
//! `F_k(P) = int_[0,1]^2 sum_(a+b=k) C(k, a) |d_u^a d_v^b P|^2`, `k = FAIRNESS_ORDER = 4`
//! (plus a ridge of `1e-12` of the largest diagonal entry, to keep the minimiser unique). On the
//! real rings of `tests/it/g1cap.rs` `F_4` gave the smallest cap curvature ranges of `F_2`, `F_3`, `F_4` (for
//! example Catmull-Clark, saddle c-net, `n = 8`: Gauss curvature down to -4.4, -2.2, -1.5 against
//! the last ring's -0.22), and `F_4` vanishes on surfaces of total degree 3, which a regular
//! hole therefore reproduces exactly. The solve: the remaining rows `E y = B q` over the
//! non-eliminated coefficients `y`, `y = E^+ B q + Z z` (`Z` a null-space basis), `z` the energy
//! minimiser; pseudo-inverse and null space from the symmetric eigen-decomposition of `E^T E`
//! (see `map.rs` for why not an SVD). The result is one matrix: cap coefficients = matrix x data.
//!
//! # Which degree, and why it is the lowest certified
//!
//! A map is *certified* when the conditions are consistent for every ring: the residual
//! `(I - E E^+) B` vanishes (below [`CERTIFIED`]) on a basis of all data that satisfy the
//! ring's local compatibility conditions (both segments define the corner block alike; at a
//! spoke end the two sectors share the point and the spoke tangent, their boundary tangents are
//! opposite, and their cross twists satisfy the relation's derivative at `u = 1`, which involves
//! data only). Any ring that is C^1 in the layout's chart satisfies them (and [`g1_cap_with`]
//! checks a given hole against them, naming the corner or spoke end that fails).
//! [`lowest_certified_degree`] tries `d = max(3, data degree), ...` and takes the first
//! certified one. The measured table (test `lowest_certified_degrees`, valences 3..=16):
//!
//! | layout, centre | bi-3 | bi-4 | bi-5 |
//! | --- | --- | --- | --- |
//! | quad, tangent plane | `n = 4` only | odd `n` and 4 | all |
//! | quad, quadratic jet | none | `n = 3, 4` | all |
//! | triangle (kites), tangent plane | (data degree 4) | odd `n`, 4, 6 | all |
//! | triangle (kites), quadratic jet | (data degree 4) | `n = 3, 6` | all |
//!
//! Why bi-4 fails for even `n` (tangent plane): with the outer two layers fixed the unknowns of
//! spoke `s` enter the relation only through the spoke coefficient `b_20` and the sums
//! `S_i = b^s_(i1) + b^(s-1)_(1i)`, `i = 1, 2`; the three middle coefficients of the degree-5
//! relation determine `S_2`, then `S_1` twice (so `b_20` is fixed by the data), and the
//! circulant `S_1 = b^s_11 + b^(s-1)_11` is singular for even `n`: a condition on the data that
//! a ring does not satisfy (certificate 1e-2). At bi-5 each spoke keeps one free vector and the
//! enclosure condition is met. The jet ties `b_20` and `S_1` to the common Hessian, which bi-4
//! cannot afford beyond `n = 3, 4`. Splitting a sector into C^2-joined pieces (below, "Split
//! sectors") does not lower the degree either: measured, the same degrees certify.
//! A cap is never of lower degree than the ring's segments (bi-6 for guided bi-6 rings).
//!
//! # Split sectors (macro-patch rings)
//!
//! Where the last ring's inner sides are splines of `m` polynomial pieces (QAS+^3: `m = 2`,
//! bi-3; guided-bi4-macro: `m = 2`, bi-4; guided-bi3-macro: `m = 3`, bi-3), a sector is an
//! `m x m` grid of bi-`d` pieces ([`Layout::Split`], conventions in [`hole`]). The conditions
//! are those above, imposed piece by piece: the two outer layers of every outer piece from its
//! ring piece (C^1, per unit of the piece's parameter); centre, spoke tangents (divided by `m`)
//! and the jet (second derivatives divided by `m^2`) on the centre piece; C^0 and the spoke
//! relation on each of the `m` spoke pieces with the *same* weight `w(u)` of the whole spoke,
//! restricted to the piece's interval (its Bernstein coefficients by the blossom), as a
//! polynomial identity; and C^2 across the inner grid lines (the rings are C^2 splines, so the
//! sector is one C^2 spline on its grid). The compatibility conditions add, per knot of each
//! side, C^2 of the boundary and of the cross derivative. `F_4` is summed over all pieces. The
//! one-patch layouts are the case `m = 1` with the same rows in the same order (their maps and
//! outputs are unchanged).
//!
//! Measured certificates ([`CapMap::new`] per degree on valences 3..8; the table of
//! `split_lowest_certified_degrees` over 3..16 is an ignored test because the `m = 3` maps take
//! minutes): splitting does **not** lower the degree. The obstruction is at the centre (the
//! circulant enclosure condition of even `n` on the centre piece's `S_1`, and the jet), which
//! a split leaves as it is:
//!
//! | `m`, data degree, centre | lowest certified degree (certificate) |
//! | --- | --- |
//! | 2, 3 or 4, tangent plane | bi-4 at odd `n = 5..15` (3e-11..7e-11), bi-3 (data 3) / bi-4 (data 4) at `n = 4`, bi-5 at `n = 3` (bi-4: 1.1e-10, just above [`CERTIFIED`]) and even `n` (<= 2e-12); measured over 3..16 |
//! | 2, 3 or 4, quadratic jet | bi-5 at every `n != 4` (<= 3e-12; bi-4 4e-10 at `n = 3`, >= 2e-3 elsewhere), bi-3 / bi-4 at `n = 4`; measured over 3..16 |
//! | 3, 3, tangent plane | bi-5 at every `n != 4` (<= 5e-11): bi-4 is consistent at odd `n` but measures 7e-10..2e-9, above [`CERTIFIED`], so it is not taken; measured over 3..8 |
//! | 3, 3, quadratic jet | bi-5 at every `n != 4` (<= 7e-12); measured over 3..8 |
//!
//! Inconsistent degrees measure 5e-5 and more (even `n` at bi-4: 4.7e-4 for `m = 2`, 5.7e-5
//! for `m = 3`). So QAS+^3's and guided-bi4-macro's caps are bi-4 at odd `n >= 5` and bi-5
//! elsewhere, guided-bi3-macro's bi-5 at every valence (the threshold is not relaxed for the
//! larger `m = 3` systems, whose rounding is higher).
//!
//! # Open fans (extraordinary boundary vertices)
//!
//! At a boundary vertex of `n >= 3` quads the hole is an open fan ([`Layout::OpenQuad`],
//! [`Hole::is_open`]): `n` quad sectors, `n + 1` spokes over a half-turn,
//! `t_s = cos(pi s / n) T0 + sin(pi s / n) T1` (so `T0` is the boundary curve's direction at
//! the centre, spokes `0` and `n` run along the boundary, `t_n = -t_0`). The conditions are
//! those above with the angle `pi / n` for `2 pi / n`: C^1 to the ring (its two outer layers),
//! centre and spoke tangents, C^0 and the relation with `w(0) = 2 cos(pi / n)` on the `n - 1`
//! inner spokes only; spokes `0` and `n` are free boundary curves whose two outer coefficients
//! are the ring's, so the surface's boundary is C^1 where the cap meets the ring. The ring's
//! compatibility conditions are those of the corners and of the inner spoke ends. The chart
//! fit of the tangents ([`ring::chart_tangents`]) takes the `n + 1` spokes (the last one off
//! segment `b` of the last sector) and solves the 2 x 2 least squares of the half-turn.
//!
//! Without a closed cycle there is no circulant enclosure condition: the twists at the centre
//! form a chain of `n - 1` equations in `n` unknowns. Measured certificates (test
//! `open_fans_are_certified_and_g1_on_their_inner_spokes`, `n = 3..12`, data degree 3): bi-3
//! fails (0.7 and more), **bi-4 is certified at every `n`** with the tangent plane (<= 5e-14);
//! with the quadratic jet bi-4 only at `n = 3, 4` (1e-12; 0.14 and more above), bi-5 at every
//! `n`. The default cap of an open fan ([`Centre::Auto`]) is bi-4 with the tangent plane at
//! every `n`, without the jet even where bi-4 affords it: at a boundary vertex the limit has
//! no bounded quadratic expansion to share (Catmull-Clark's ring curvature grows about 3x per
//! ring at a boundary vertex of 4 quads, its subdominant eigenvalue `0.611` against the
//! boundary's `1/2`), and the jet made the cap worse where it was tried: Gauss curvature down
//! to -162 and `|H|` up to 21 on the notched c-net at 4 rings, against -69 and 3.5 without it
//! (the last ring: -4.4 and 0.8); on the L-shape (3 quads) -1.6e-2 against -2.1e-2.
//!
//! ## Open fans of triangles (Loop)
//!
//! At a boundary vertex of `n` triangles ([`Layout::OpenTriangle`], conventions in [`hole`])
//! each fan triangle is one cap patch with a straight corner at the midpoint `M_s` of its outer
//! edge (kites, which the closed fans use, would leave a half-triangle at each boundary spoke).
//! The spokes end at the spoke ends `E_s` themselves, where the two fan triangles' cross
//! derivatives are not opposite: the weight is `w(u) = 2 cos(pi / n) (1 - u)^2 + (2 w1 + kappa)
//! u (1 - u) + w1 u^2` with `w1 = w(1) = -1/2` and `kappa = -w'(1) = 3/2`, both read off the
//! lattice chart at `E_s` (the sum of the two pieces' cross derivatives there is `-(E_s - C) /
//! 2`, the sum of their bilinear twists `-3/2 (E_s - C)`). With `w1 != 0` the relation's
//! derivative at the spoke end holds the cap's own second derivative along the spoke, so it
//! is a condition on the cap, not on the ring; the ring's compatibility at an inner spoke end is
//! the relation itself there, `R(1) = 0`. Measured certificates (test
//! `open_triangle_fans_are_certified`, data degrees (4, 3)): bi-4 only at `n = 1` (a corner)
//! and `n = 3` (the regular boundary), **bi-5 at every `n = 1..12`** (<= 1.1e-12). At `M_s`
//! the patch's parametrisation is singular (`du = -dv`), but its two outer layers along both
//! sides make its value and derivatives up to third order there the ring's: the surface is G^1
//! there with bounded curvature. One triangle at a corner vertex (Loop's corner rule keeps it
//! and its two boundary edges' directions) is one sector whose spokes are `T0` and `T1`
//! themselves: a quarter-turn of the chart, no inner spoke.
//!
//! ## Crease fans
//!
//! Beside an infinitely sharp crease through the centre each side is an open fan
//! ([`Fan::Crease`]) whose boundary spokes must be shared exactly with the other side's cap
//! (or its regular patches). Two changes make them so: `T0` is the provider's exact derivative
//! of the crease at the centre instead of the chart fit (only `T1` is fitted given it,
//! [`ring::crease_tangents`]), and each boundary spoke is the cubic Hermite interpolant of its
//! end data: the centre with `t_0` (or `t_n`), the spoke end with the ring's derivative there
//! (rows fixing its coefficients `2 ..= d - 2`). For a crease under OpenSubdiv's rules the
//! crease is the cubic B-spline of its polygon and those are its own end data, so the spoke is
//! the crease's limit curve. The fixed coefficients enter no other condition, so the open
//! layouts keep their certificates and lowest degrees (test
//! `crease_fans_keep_the_certificates_and_put_hermite_cubics_on_their_boundary_spokes`:
//! `OpenQuad` and `OpenTriangle` n = 1..10, `d - 3` fewer free parameters per boundary
//! spoke).
//!
//! ## Dart fans
//!
//! Around a dart (one infinitely sharp edge ending at the centre) the surface has a tangent
//! plane at the centre but is only C^0 along the sharp edge. Its hole is an open fan whose
//! `n + 1` spokes span the full turn ([`Fan::Dart`]): spokes `0` and `n` are
//! both the sharp edge, `t_0 = t_n = T0`, and both are the cubic Hermite interpolant of spoke
//! `0`'s end data (the rows of the crease fans), so the two sectors beside the sharp edge share
//! it exactly; every other spoke carries the G^1 relation with `w(0) = 2 cos(2 pi / n)`, as in a
//! closed hole, but no cycle closes around the centre. The ring's data must agree at the sharp
//! spoke's end (one point, one derivative along the spoke: two compatibility rows). Lowest
//! certified degrees (test `dart_fans_are_certified_c0_on_their_sharp_spoke_and_g1_elsewhere`):
//! bi-4 for quads at every `n` from 2 to 12 (bi-3 at `n = 4`), bi-5 for Loop's triangle fans
//! (bi-4 at `n = 6`). `T0, T1` are fitted in the limit tangent plane over the full turn.
//!
//! ## Wedges
//!
//! Around an interior vertex of `m` sectors some of which are holes (OpenSubdiv's hole faces:
//! refined, but without surface) the limit is the smooth surface with those sectors cut away.
//! Each run of `n < m` present sectors is an open fan whose spokes keep the angles of the full
//! turn, `2 pi s / m` ([`Fan::Wedge`]), spokes `0` and `n` free curves on the
//! holes' border, G^1 on the `n - 1` inner spokes with `w(0) = 2 cos(2 pi / m)`. All runs share
//! the vertex's limit point and tangent plane. Lowest certified degrees (test
//! `wedges_are_certified_at_the_angles_of_the_full_turn`, `m = 3..12`): bi-4 for quads (bi-3
//! for one sector and at `m = 4`), bi-5 for triangles (bi-4 for one sector and at `m = 6`).
//!
//! ## Corner sectors
//!
//! At a corner with sharp edges (OpenSubdiv's corner rule: the vertex is its own limit) each
//! sector between two consecutive sharp edges is an open fan ([`Fan::Corner`],
//! [`Fan::Corner`]) whose boundary spokes are the sharp edges' limit curves (the Hermite rows
//! of the crease fans) and whose `T0`, `T1` are both pinned to those curves' derivatives at the
//! corner, so neighbouring sectors share each sharp edge exactly. The chart turns a quarter
//! (spoke `n` along `T1`) or, for a reflex sector, three quarters (along `-T1`), so the cap
//! turns the way its ring does instead of folding over. The corner itself is a cone point:
//! the sectors meet there C^0 only, across their sharp spokes (a corner without two sharp
//! edges: "Cone points" below). Lowest certified degree
//! (test `corner_sectors_are_certified_with_both_sharp_spokes_pinned`, `n = 1..10`): bi-4,
//! bi-3 for one sector.
//!
//! ## Cone points
//!
//! A vertex the corner rule keeps (sharpness infinity) with no infinitely sharp edge, or one,
//! has no tangent plane: the limit surface has a tangent cone there, smooth along every other
//! direction. Its hole is closed ([`Fan::Cone`]) or a dart's fan ([`Fan::DartCone`]), centred
//! at the vertex with every spoke tangent zero ([`Fan::Cone`]): the cap's corners at the apex
//! are singular, and the G^1 relation `D_v P_s + D_u P_(s-1) = w D_u P_s` along each spoke,
//! whose three terms all vanish at the apex, holds as the polynomial identity it is. Divided
//! by the spoke's parameter it still holds at the apex itself, on the second-order data: near
//! the apex sector `s` is `Q_s(u, v) = a_s u^2 + b_s u v + a_(s+1) v^2`, the relation there
//! reads `b_(s-1) + b_s = 2 w(0) a_s`, so each pair of sectors shares the plane of `a_s` and
//! `b_(s-1) + b_s` along their spoke: G^1 along the spoke up to the apex, where the planes of
//! different spokes differ (the cone). `w(0) = 2 cos(pi / n)`, the chart of a half-turn: in
//! the model of a plane `Q_s = (u e_s + v e_(s+1))^2` (complex numbers, `e_s = exp(i pi s / n)`:
//! squaring doubles the chart's angles to the full turn) the relation holds with that weight.
//! No jet at the centre. In a dart's fan the sharp spoke is the cubic `C, C, E + X / 3, E` of
//! its end data and each inner spoke's second-order coefficient is that cubic's
//! (`system::cone_spoke_rows`: left free, the fairness functional bent them towards the sharp
//! spoke and folded a sector over). The free coefficients minimise the fairness functional.
//! Lowest certified degrees (test
//! `cone_fans_are_certified_with_zero_spoke_tangents_and_g1_spokes`, `n = 3..12`): closed,
//! bi-4 at odd `n` and bi-5 at even `n` (quads and Loop's triangles), bi-3 for two quad
//! sectors (`w(0) = 2 cos(pi / 2) = 0`; test `cones_of_two_sectors_are_certified`, a corner
//! tag on a valence-2 vertex; its apex is sharper, neighbouring normals near it up to 40
//! degrees apart on a 40 x 40 grid, `tests/it/cone_caps.rs`); a dart's fan bi-4 for
//! quads, bi-6 for triangles (bi-5 at `n = 3`). Not a published construction.
//!
//! # Two sectors (valence 2)
//!
//! A closed hole of two quad sectors (an interior vertex of valence 2: Catmull-Clark's after a
//! pentagon's first step, non-box's pillow of two cells) has opposite spoke tangents,
//! `t_1 = -t_0 = -T0` (`w(0) = 2 cos(pi) = -2`), so each sector's corner at the centre is
//! singular and the spokes fix no tangent plane: the conditions above leave the normal at the
//! centre to the fairness functional. The centre condition of two sectors is instead the
//! **half-plane jet** (`centre::half_plane_rows`, always on for `n = 2`, whatever [`Centre`]):
//! each sector is `q o phi_s + O(3)` for the half-plane charts
//! `phi_s(u, v) = u e_s + v e_(s+1) + (w'(0) / 4) (u^2 e_s + v^2 e_(s+1)) + k u v f_s`,
//! `e_0 = -e_1 = T0`, `f_0 = -f_1 = T1`, `k = 1`, and a quadratic `q` whose one free vector is
//! the coefficient `H` of `x^2 / 2` (the other Hessian terms are of third order through the
//! chart). The charts satisfy the spoke relation with `w(0) = -2` and its first derivative at
//! the centre, and `det D phi_s = k (u + v) + O(2) > 0` on the sector, so every sector's normal
//! tends to `T0 x T1` from every direction: the cap is G^1 at the centre. Given the relation,
//! the rows are also necessary for that: the relation leaves `d_uu P_0` and `d_uv P_0` free at
//! the centre, and sector 0's normal there is
//! `u T0 x (d_uu + d_uv) P_0 + v T0 x (d_uv + d_vv) P_0`, along the plane's normal for every
//! direction only if `(d_uv + d_vv) P_0` lies in the plane with a positive `T1` part; a linear
//! condition fixes that part (here `k T1 - (w'(0) / 2) T0`) and leaves `H`.
//!
//! `T0` and `T1` are fitted to chords of the chart, projected into the plane
//! ([`ring::chart_tangents`]): the spoke ends, `phi_0(1, 0) = (1 + w'(0) / 4) T0 = 2 T0`, and
//! the sectors' corners, `phi_0(1, 1) = k T1`. Not to the spoke derivatives of the other holes:
//! at valence 2 Catmull-Clark's and non-box's rings contract by 1/4 per step, so their spokes
//! are quadratic at the centre and that fit vanishes (1e-8 of the hole: a cusp whose corner
//! normals were rounding, 3.14 rad apart at 8 rings on the cube with every edge split). A
//! provider gives the plane (Catmull-Clark: the eigen tangents `e_0 - e_1`, `f_0 - f_1`,
//! non-box: the spoke ends' and FCVs' differences).
//! Measured certificates (test `two_sector_certificates`): bi-3 6.0, bi-4 1.2, **bi-5
//! 8.6e-14** (13 free parameters per coordinate), for the split layouts bi-4 1.1e-2 (`m = 2`)
//! and 1.4e-3 (`m = 3`), bi-5 9.9e-13 and 5.3e-12: the cap of two sectors is bi-5 on every
//! quad layout. Loop's triangle fans and the other fans keep at least 3 sectors.
//!
//! Since `phi_s` is singular at the centre (`|phi_s| ~ u^2` along the diagonal), the cubic
//! terms of the cap are of order `|x|^(3/2)` in the chart there, and the cap's curvature grows
//! without bound towards the centre (measured by `check` on the split-edge cube at 3 rings,
//! Catmull-Clark: Gauss curvature in `[22, 2.7e5]` in the cap, `[-1.5, 1.9e2]` in the last
//! ring; `nonbox-4dir`'s octahedron `[19, 1.1e6]` against `[14, 43]`; the chart's scale `k`
//! moves these maxima by factors of 2 to 4 either way, not in order). The
//! schemes' own limits are no better at valence 2: Catmull-Clark's local matrix on `v, e_i,
//! f_i` has the double subdominant eigenvalue 1/4 (modes `e_0 - e_1`, `f_0 - f_1`) and a
//! symmetric eigenvalue -1/4 of the same modulus, so its limit has no tangent plane there (the
//! ring normals oscillate by up to 0.18 rad at every scale) and its ring curvature grows
//! (Gauss curvature up to 2.6e6 in ring 8). The cap is still G^1 at every join and at the
//! centre, with `T0 x T1` the plane of the two subdominant modes. The contraction 1/4 has a
//! price in precision: the ring data's rounding, relative to the hole, grows 4 times per ring
//! (2 times at other valences). Catmull-Clark on the cube with every edge split: G^1 at most
//! 2.2e-10 rad at 8 rings, 3.0e-9 at 10, 1.7e-8 at 12 (the rings' own joins there: 5.5e-9);
//! at 15 the data fail the compatibility check (relative defect 7e-7) and the fill closes
//! the hole, with a note.
//!
//! # Data that are not enough
//!
//! The cap needs value and first cross derivative of a ring that is C^1 in the layout's chart
//! at every spoke end and corner. Polar rings (PolBS: one segment per sector whose boundary is
//! smooth through the spoke ends, collapsed patches at the pole) do not fit either layout: their
//! spoke ends are flat points of the boundary, where a quad or kite corner would be degenerate;
//! PolBS's own collapsed bi-2 cap is G^1 there (see `schemes::bi2::surface`). Triangle
//! rings must be a three-direction lattice at the spoke ends (valence 6), as Loop's are.

mod centre;
mod choose;
mod compat;
mod conversion;
mod fan;
pub mod hole;
mod map;
pub mod ring;
#[cfg(feature = "unit-tests")]
mod split_tests;
mod system;
#[cfg(feature = "unit-tests")]
mod tests;
#[cfg(feature = "unit-tests")]
mod two_tests;

pub use choose::{
    Cap, CapOptions, MAX_CAP_VALENCE, MAX_COMPATIBILITY_DEFECT, cap_choice, cap_map, g1_cap,
    g1_cap_with, hole_cap_map, lowest_certified_degree, lowest_certified_fan,
};
pub use hole::{CornerAngle, Degrees, Fan, Hole, Layout, QuadHole, Segment, spoke_tangent};
pub use map::{CERTIFIED, CapMap, Centre, FAIRNESS_ORDER};
