//! Butcher tableau of DOP853 (Dormand & Prince, in the form of Hairer's
//! `dop853.f`), with the three extra stages and the coefficients of the
//! 7th-order dense output.
//!
//! The numbers are those of scipy's `integrate/_ivp/dop853_coefficients.py`,
//! which are Hairer's, copied digit for digit and laid out the same way
//! (0-based stage indices), so the two files can be compared line by line.
//! Literals carry more digits than an `f64` holds; the compiler rounds each to
//! the nearest `f64`, exactly as scipy's parser does. The tests at the bottom
//! check the order conditions, which catch any mistyped digit that matters.
//!
//! Stage layout: stages `0..12` are the main method (stage 11 has `c = 1`),
//! stage 12 is `f(t + h, y_new)` (first-same-as-last, its row of `A` is the
//! 8th-order weights `B`), stages `13..16` are the extra dense-output stages.

// The literals keep all the digits of the published tables, on purpose: they
// can then be compared with the source character by character.
#![allow(clippy::excessive_precision)]

/// Stages of the main method (without the FSAL stage).
pub(super) const N_STAGES: usize = 12;
/// Stages including the FSAL stage and the three dense-output stages.
pub(super) const N_STAGES_EXTENDED: usize = 16;
/// Number of rows of [`D`]: coefficients 4..7 of the dense polynomial (the
/// first three come from `y_old`, `y_new`, `f_old` and `f_new`).
pub(super) const N_DENSE_ROWS: usize = 4;

/// Nodes `c_i`.
pub(super) const C: [f64; N_STAGES_EXTENDED] = [
    0.0,
    0.526001519587677318785587544488e-01,
    0.789002279381515978178381316732e-01,
    0.118350341907227396726757197510,
    0.281649658092772603273242802490,
    0.333333333333333333333333333333,
    0.25,
    0.307692307692307692307692307692,
    0.651282051282051282051282051282,
    0.6,
    0.857142857142857142857142857142,
    1.0,
    1.0,
    0.1,
    0.2,
    0.777777777777777777777777777778,
];

/// Runge–Kutta matrix `a_ij` (row `i` uses stages `j < i`).
pub(super) const A: [[f64; N_STAGES_EXTENDED]; N_STAGES_EXTENDED] = build_a();

const fn build_a() -> [[f64; N_STAGES_EXTENDED]; N_STAGES_EXTENDED] {
    let mut a = [[0.0; N_STAGES_EXTENDED]; N_STAGES_EXTENDED];
    a[1][0] = 5.26001519587677318785587544488e-2;

    a[2][0] = 1.97250569845378994544595329183e-2;
    a[2][1] = 5.91751709536136983633785987549e-2;

    a[3][0] = 2.95875854768068491816892993775e-2;
    a[3][2] = 8.87627564304205475450678981324e-2;

    a[4][0] = 2.41365134159266685502369798665e-1;
    a[4][2] = -8.84549479328286085344864962717e-1;
    a[4][3] = 9.24834003261792003115737966543e-1;

    a[5][0] = 3.7037037037037037037037037037e-2;
    a[5][3] = 1.70828608729473871279604482173e-1;
    a[5][4] = 1.25467687566822425016691814123e-1;

    a[6][0] = 3.7109375e-2;
    a[6][3] = 1.70252211019544039314978060272e-1;
    a[6][4] = 6.02165389804559606850219397283e-2;
    a[6][5] = -1.7578125e-2;

    a[7][0] = 3.70920001185047927108779319836e-2;
    a[7][3] = 1.70383925712239993810214054705e-1;
    a[7][4] = 1.07262030446373284651809199168e-1;
    a[7][5] = -1.53194377486244017527936158236e-2;
    a[7][6] = 8.27378916381402288758473766002e-3;

    a[8][0] = 6.24110958716075717114429577812e-1;
    a[8][3] = -3.36089262944694129406857109825;
    a[8][4] = -8.68219346841726006818189891453e-1;
    a[8][5] = 2.75920996994467083049415600797e1;
    a[8][6] = 2.01540675504778934086186788979e1;
    a[8][7] = -4.34898841810699588477366255144e1;

    a[9][0] = 4.77662536438264365890433908527e-1;
    a[9][3] = -2.48811461997166764192642586468;
    a[9][4] = -5.90290826836842996371446475743e-1;
    a[9][5] = 2.12300514481811942347288949897e1;
    a[9][6] = 1.52792336328824235832596922938e1;
    a[9][7] = -3.32882109689848629194453265587e1;
    a[9][8] = -2.03312017085086261358222928593e-2;

    a[10][0] = -9.3714243008598732571704021658e-1;
    a[10][3] = 5.18637242884406370830023853209;
    a[10][4] = 1.09143734899672957818500254654;
    a[10][5] = -8.14978701074692612513997267357;
    a[10][6] = -1.85200656599969598641566180701e1;
    a[10][7] = 2.27394870993505042818970056734e1;
    a[10][8] = 2.49360555267965238987089396762;
    a[10][9] = -3.0467644718982195003823669022;

    a[11][0] = 2.27331014751653820792359768449;
    a[11][3] = -1.05344954667372501984066689879e1;
    a[11][4] = -2.00087205822486249909675718444;
    a[11][5] = -1.79589318631187989172765950534e1;
    a[11][6] = 2.79488845294199600508499808837e1;
    a[11][7] = -2.85899827713502369474065508674;
    a[11][8] = -8.87285693353062954433549289258;
    a[11][9] = 1.23605671757943030647266201528e1;
    a[11][10] = 6.43392746015763530355970484046e-1;

    a[12][0] = 5.42937341165687622380535766363e-2;
    a[12][5] = 4.45031289275240888144113950566;
    a[12][6] = 1.89151789931450038304281599044;
    a[12][7] = -5.8012039600105847814672114227;
    a[12][8] = 3.1116436695781989440891606237e-1;
    a[12][9] = -1.52160949662516078556178806805e-1;
    a[12][10] = 2.01365400804030348374776537501e-1;
    a[12][11] = 4.47106157277725905176885569043e-2;

    a[13][0] = 5.61675022830479523392909219681e-2;
    a[13][6] = 2.53500210216624811088794765333e-1;
    a[13][7] = -2.46239037470802489917441475441e-1;
    a[13][8] = -1.24191423263816360469010140626e-1;
    a[13][9] = 1.5329179827876569731206322685e-1;
    a[13][10] = 8.20105229563468988491666602057e-3;
    a[13][11] = 7.56789766054569976138603589584e-3;
    a[13][12] = -8.298e-3;

    a[14][0] = 3.18346481635021405060768473261e-2;
    a[14][5] = 2.83009096723667755288322961402e-2;
    a[14][6] = 5.35419883074385676223797384372e-2;
    a[14][7] = -5.49237485713909884646569340306e-2;
    a[14][10] = -1.08347328697249322858509316994e-4;
    a[14][11] = 3.82571090835658412954920192323e-4;
    a[14][12] = -3.40465008687404560802977114492e-4;
    a[14][13] = 1.41312443674632500278074618366e-1;

    a[15][0] = -4.28896301583791923408573538692e-1;
    a[15][5] = -4.69762141536116384314449447206;
    a[15][6] = 7.68342119606259904184240953878;
    a[15][7] = 4.06898981839711007970213554331;
    a[15][8] = 3.56727187455281109270669543021e-1;
    a[15][12] = -1.39902416515901462129418009734e-3;
    a[15][13] = 2.9475147891527723389556272149;
    a[15][14] = -9.15095847217987001081870187138;
    a
}

/// 8th-order weights `b_j` (row 12 of [`A`], as in scipy: `B = A[12, :12]`).
pub(super) const B: [f64; N_STAGES] = build_b();

const fn build_b() -> [f64; N_STAGES] {
    let mut b = [0.0; N_STAGES];
    let mut j = 0;
    while j < N_STAGES {
        b[j] = A[N_STAGES][j];
        j += 1;
    }
    b
}

/// Weights of the 3rd-order error estimator: `B` minus Hairer's `bhh1..3`
/// (scipy `E3`, without its trailing zero for the FSAL stage).
pub(super) const E3: [f64; N_STAGES] = build_e3();

const fn build_e3() -> [f64; N_STAGES] {
    let mut e = B;
    e[0] -= 0.244094488188976377952755905512;
    e[8] -= 0.733846688281611857341361741547;
    e[11] -= 0.220588235294117647058823529412e-1;
    e
}

/// Weights of the 5th-order error estimator (Hairer's `er1..er12`, scipy
/// `E5` without its trailing zero).
pub(super) const E5: [f64; N_STAGES] = build_e5();

const fn build_e5() -> [f64; N_STAGES] {
    let mut e = [0.0; N_STAGES];
    e[0] = 0.1312004499419488073250102996e-1;
    e[5] = -0.1225156446376204440720569753e1;
    e[6] = -0.4957589496572501915214079952;
    e[7] = 0.1664377182454986536961530415e1;
    e[8] = -0.3503288487499736816886487290;
    e[9] = 0.3341791187130174790297318841;
    e[10] = 0.8192320648511571246570742613e-1;
    e[11] = -0.2235530786388629525884427845e-1;
    e
}

/// Dense-output coefficients `d_rj` for the polynomial's terms 4..7 (Hairer's
/// `d41..d716`, scipy `D`).
pub(super) const D: [[f64; N_STAGES_EXTENDED]; N_DENSE_ROWS] = build_d();

const fn build_d() -> [[f64; N_STAGES_EXTENDED]; N_DENSE_ROWS] {
    let mut d = [[0.0; N_STAGES_EXTENDED]; N_DENSE_ROWS];
    d[0][0] = -0.84289382761090128651353491142e1;
    d[0][5] = 0.56671495351937776962531783590;
    d[0][6] = -0.30689499459498916912797304727e1;
    d[0][7] = 0.23846676565120698287728149680e1;
    d[0][8] = 0.21170345824450282767155149946e1;
    d[0][9] = -0.87139158377797299206789907490;
    d[0][10] = 0.22404374302607882758541771650e1;
    d[0][11] = 0.63157877876946881815570249290;
    d[0][12] = -0.88990336451333310820698117400e-1;
    d[0][13] = 0.18148505520854727256656404962e2;
    d[0][14] = -0.91946323924783554000451984436e1;
    d[0][15] = -0.44360363875948939664310572000e1;

    d[1][0] = 0.10427508642579134603413151009e2;
    d[1][5] = 0.24228349177525818288430175319e3;
    d[1][6] = 0.16520045171727028198505394887e3;
    d[1][7] = -0.37454675472269020279518312152e3;
    d[1][8] = -0.22113666853125306036270938578e2;
    d[1][9] = 0.77334326684722638389603898808e1;
    d[1][10] = -0.30674084731089398182061213626e2;
    d[1][11] = -0.93321305264302278729567221706e1;
    d[1][12] = 0.15697238121770843886131091075e2;
    d[1][13] = -0.31139403219565177677282850411e2;
    d[1][14] = -0.93529243588444783865713862664e1;
    d[1][15] = 0.35816841486394083752465898540e2;

    d[2][0] = 0.19985053242002433820987653617e2;
    d[2][5] = -0.38703730874935176555105901742e3;
    d[2][6] = -0.18917813819516756882830838328e3;
    d[2][7] = 0.52780815920542364900561016686e3;
    d[2][8] = -0.11573902539959630126141871134e2;
    d[2][9] = 0.68812326946963000169666922661e1;
    d[2][10] = -0.10006050966910838403183860980e1;
    d[2][11] = 0.77771377980534432092869265740;
    d[2][12] = -0.27782057523535084065932004339e1;
    d[2][13] = -0.60196695231264120758267380846e2;
    d[2][14] = 0.84320405506677161018159903784e2;
    d[2][15] = 0.11992291136182789328035130030e2;

    d[3][0] = -0.25693933462703749003312586129e2;
    d[3][5] = -0.15418974869023643374053993627e3;
    d[3][6] = -0.23152937917604549567536039109e3;
    d[3][7] = 0.35763911791061412378285349910e3;
    d[3][8] = 0.93405324183624310003907691704e2;
    d[3][9] = -0.37458323136451633156875139351e2;
    d[3][10] = 0.10409964950896230045147246184e3;
    d[3][11] = 0.29840293426660503123344363579e2;
    d[3][12] = -0.43533456590011143754432175058e2;
    d[3][13] = 0.96324553959188282948394950600e2;
    d[3][14] = -0.39177261675615439165231486172e2;
    d[3][15] = -0.14972683625798562581422125276e3;
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Row sums `sum_j a_ij = c_i`: every stage is consistent. Catches most
    /// transcription slips in `A` and `C`.
    #[test]
    fn row_sums_equal_nodes() {
        for i in 1..N_STAGES_EXTENDED {
            let s: f64 = A[i][..i].iter().sum();
            assert!((s - C[i]).abs() < 1e-14, "row {i}: {s} vs {}", C[i]);
        }
    }

    /// The quadrature order conditions `sum_j b_j c_j^k = 1/(k+1)` for
    /// k = 0..7 (the bushy-tree conditions of an 8th-order method).
    #[test]
    fn weights_integrate_polynomials_to_degree_7() {
        for k in 0..8 {
            let s: f64 = (0..N_STAGES).map(|j| B[j] * C[j].powi(k)).sum();
            let want = 1.0 / f64::from(k + 1);
            assert!((s - want).abs() < 1e-13, "k = {k}: {s} vs {want}");
        }
    }

    /// The error estimators are differences of consistent methods, so their
    /// weights sum to zero (and integrate constants and low-order polynomials
    /// exactly: `sum e_j c_j^k = 0` for k below their order).
    #[test]
    fn error_weights_annihilate_low_order_polynomials() {
        for k in 0..3 {
            let s3: f64 = (0..N_STAGES).map(|j| E3[j] * C[j].powi(k)).sum();
            assert!(s3.abs() < 1e-13, "E3, k = {k}: {s3}");
        }
        for k in 0..5 {
            let s5: f64 = (0..N_STAGES).map(|j| E5[j] * C[j].powi(k)).sum();
            assert!(s5.abs() < 1e-13, "E5, k = {k}: {s5}");
        }
    }

    /// For `y' = 1` all stages are 1 and the dense terms 4..7 must vanish,
    /// i.e. each row of `D` sums to zero.
    #[test]
    fn dense_rows_sum_to_zero() {
        for (r, row) in D.iter().enumerate() {
            let s: f64 = row.iter().sum();
            assert!(s.abs() < 1e-11, "row {r}: {s}");
        }
    }

    /// Every stage of a step feeds something tested for finiteness: a later
    /// stage, the solution or an error estimate. The stepper relies on it
    /// to test only `y_new` and the error instead of every stage.
    #[test]
    fn every_stage_feeds_the_solution_or_the_error() {
        for j in 0..N_STAGES {
            let later = (j + 1..N_STAGES).any(|i| A[i][j] != 0.0);
            assert!(
                later || B[j] != 0.0 || E5[j] != 0.0 || E3[j] != 0.0,
                "stage {j} feeds nothing"
            );
        }
    }
}
