//! The series palette stays apart for colour-blind viewers, and no two
//! series look alike.

use super::*;

/// Machado, Oliveira & Fernandes (2009) simulation matrices at severity 1,
/// on linear RGB: protanopia, deuteranopia, tritanopia; then normal vision.
const VISIONS: [(&str, [[f64; 3]; 3]); 4] = [
    (
        "protanopia",
        [
            [0.152286, 1.052583, -0.204868],
            [0.114503, 0.786281, 0.099216],
            [-0.003882, -0.048116, 1.051998],
        ],
    ),
    (
        "deuteranopia",
        [
            [0.367322, 0.860646, -0.227968],
            [0.280085, 0.672501, 0.047413],
            [-0.011820, 0.042940, 0.968881],
        ],
    ),
    (
        "tritanopia",
        [
            [1.255528, -0.076749, -0.178779],
            [-0.078411, 0.930809, 0.147602],
            [0.004733, 0.691367, 0.303900],
        ],
    ),
    (
        "normal",
        [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    ),
];

/// sRGB as seen with `m`, in CIELAB (D65).
fn seen(c: [u8; 3], m: &[[f64; 3]; 3]) -> [f64; 3] {
    let lin = |v: u8| {
        let v = f64::from(v) / 255.0;
        if v <= 0.04045 {
            v / 12.92
        } else {
            ((v + 0.055) / 1.055).powf(2.4)
        }
    };
    let rgb = c.map(lin);
    let s: Vec<f64> = (0..3)
        .map(|i| {
            (0..3)
                .map(|j| m[i][j] * rgb[j])
                .sum::<f64>()
                .clamp(0.0, 1.0)
        })
        .collect();
    let xyz = [
        (0.4124 * s[0] + 0.3576 * s[1] + 0.1805 * s[2]) / 0.95047,
        0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2],
        (0.0193 * s[0] + 0.1192 * s[1] + 0.9505 * s[2]) / 1.08883,
    ];
    let f = |t: f64| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let [fx, fy, fz] = xyz.map(f);
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The least CIE76 ΔE between two colours of `palette` seen with `m`.
fn least_difference(palette: &[[u8; 3]], m: &[[f64; 3]; 3]) -> f64 {
    let lab: Vec<[f64; 3]> = palette.iter().map(|&c| seen(c, m)).collect();
    let mut least = f64::INFINITY;
    for i in 0..lab.len() {
        for j in 0..i {
            let d = (0..3).map(|k| (lab[i][k] - lab[j][k]).powi(2)).sum::<f64>();
            least = least.min(d.sqrt());
        }
    }
    least
}

#[test]
fn the_palette_stays_apart_under_colour_blindness() {
    // ΔE 15 is far beyond a just-noticeable difference (about 2.3).
    for (vision, m) in &VISIONS {
        let d = least_difference(&PALETTE, m);
        assert!(d >= 15.0, "{vision}: two colours are only ΔE {d:.1} apart");
    }
    // The check has teeth: Tableau 10 (the page's old scheme) fails it, its
    // red and green nearly one colour under deuteranopia.
    let tableau: Vec<[u8; 3]> = [
        0x4e79a7, 0xf28e2c, 0xe15759, 0x76b7b2, 0x59a14f, 0xedc949, 0xaf7aa1, 0xff9da7, 0x9c755f,
        0xbab0ab,
    ]
    .iter()
    .map(|&h: &u32| [(h >> 16) as u8, (h >> 8) as u8, h as u8])
    .collect();
    assert!(least_difference(&tableau, &VISIONS[1].1) < 2.0);
}

#[test]
fn no_two_of_the_first_hundred_series_look_alike() {
    let styles: Vec<SeriesStyle> = (0..100).map(series_style).collect();
    for i in 0..styles.len() {
        for j in 0..i {
            let (a, b) = (styles[i], styles[j]);
            assert!(
                a.colour != b.colour || a.marker != b.marker,
                "series {j} and {i} share colour and marker"
            );
        }
    }
    // The first ten (the σ-sweep's series) differ in all three.
    for i in 0..10 {
        for j in 0..i {
            let (a, b) = (styles[i], styles[j]);
            assert!(a.colour != b.colour && a.marker != b.marker, "{j} {i}");
        }
    }
    assert_eq!(
        serde_json::to_string(&series_style(1)).unwrap(),
        r##"{"colour":"#ffa90e","dash":[9,4],"marker":"square"}"##
    );
}
