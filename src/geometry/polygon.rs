//! Simple 2D polygons (floors, footprints): area, orientation, containment, triangulation.

use super::GeometryError;

/// Signed area of a closed polygon (positive when counter-clockwise).
pub fn signed_area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| {
            let a = ring[i];
            let b = ring[(i + 1) % n];
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        * 0.5
}

/// Axis-aligned bounds `(min, max)` of a ring.
pub fn bounds(ring: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in ring {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (lo, hi)
}

/// True when `p` lies inside (or on the boundary of) the polygon.
pub fn contains(ring: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let a = ring[i];
        let b = ring[(i + 1) % n];
        if point_on_segment(p, a, b) {
            return true;
        }
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

fn point_on_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> bool {
    let cross = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    if cross.abs() > 1e-9 {
        return false;
    }
    let dot = (p[0] - a[0]) * (b[0] - a[0]) + (p[1] - a[1]) * (b[1] - a[1]);
    let len2 = (b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2);
    dot >= -1e-12 && dot <= len2 + 1e-12
}

/// True when every interior angle turns the same way (counter-clockwise ring assumed).
pub fn is_convex(ring: &[[f64; 2]]) -> bool {
    let n = ring.len();
    if n < 3 {
        return false;
    }
    (0..n).all(|i| {
        let a = ring[i];
        let b = ring[(i + 1) % n];
        let c = ring[(i + 2) % n];
        (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) >= -1e-12
    })
}

/// Convex hull of a point set, counter-clockwise, without collinear points (Andrew's monotone
/// chain). Fewer than three distinct points come back as they are (deduplicated).
pub fn convex_hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut pts: Vec<[f64; 2]> = points
        .iter()
        .copied()
        .filter(|p| p.iter().all(|v| v.is_finite()))
        .collect();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 1e-15
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Checks that a floor polygon is usable: at least 3 vertices, finite, counter-clockwise,
/// positive area.
pub fn validate_floor(ring: &[[f64; 2]]) -> Result<(), GeometryError> {
    if ring.len() < 3 {
        return Err(GeometryError::InvalidPolygon(format!(
            "{} vertices, need at least 3",
            ring.len()
        )));
    }
    if ring.iter().flatten().any(|v| !v.is_finite()) {
        return Err(GeometryError::NonFinite);
    }
    let a = signed_area(ring);
    if a <= 1e-6 {
        return Err(GeometryError::InvalidPolygon(format!(
            "signed area {a:.4} m^2: the ring must be counter-clockwise with positive area"
        )));
    }
    Ok(())
}

/// Splits a simple counter-clockwise polygon into convex pieces: the polygon itself when convex,
/// otherwise triangles by ear clipping.
pub fn convex_parts(ring: &[[f64; 2]]) -> Result<Vec<Vec<[f64; 2]>>, GeometryError> {
    validate_floor(ring)?;
    if is_convex(ring) {
        return Ok(vec![ring.to_vec()]);
    }
    let mut idx: Vec<usize> = (0..ring.len()).collect();
    let mut out = Vec::new();
    let mut guard = 0;
    while idx.len() > 3 {
        guard += 1;
        if guard > 10 * ring.len() * ring.len() {
            return Err(GeometryError::InvalidPolygon(
                "ear clipping made no progress (self-intersecting polygon?)".into(),
            ));
        }
        let n = idx.len();
        let mut clipped = false;
        for i in 0..n {
            let (ia, ib, ic) = (idx[(i + n - 1) % n], idx[i], idx[(i + 1) % n]);
            let (a, b, c) = (ring[ia], ring[ib], ring[ic]);
            let turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
            if turn <= 1e-12 {
                continue;
            }
            let tri = [a, b, c];
            let blocked = idx.iter().any(|&j| {
                j != ia && j != ib && j != ic && contains(&tri, ring[j]) && !tri.contains(&ring[j])
            });
            if blocked {
                continue;
            }
            out.push(vec![a, b, c]);
            idx.remove(i);
            clipped = true;
            break;
        }
        if !clipped {
            return Err(GeometryError::InvalidPolygon(
                "polygon has no ear (self-intersecting?)".into(),
            ));
        }
    }
    out.push(idx.iter().map(|&i| ring[i]).collect());
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_drops_inner_and_collinear_points() {
        let pts = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 0.5],
            [0.0, 1.0],
            [0.0, 1.0],
        ];
        let h = convex_hull(&pts);
        assert_eq!(h.len(), 4, "{h:?}");
        assert!((signed_area(&h) - 2.0).abs() < 1e-12);
        assert!(is_convex(&h));
        assert_eq!(convex_hull(&[[1.0, 1.0], [1.0, 1.0]]).len(), 1);
    }

    #[test]
    fn rectangle_is_one_part() {
        let r = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]];
        assert!((signed_area(&r) - 12.0).abs() < 1e-12);
        assert_eq!(convex_parts(&r).unwrap().len(), 1);
        assert!(contains(&r, [2.0, 1.0]));
        assert!(!contains(&r, [5.0, 1.0]));
    }

    #[test]
    fn l_shape_triangulates_with_full_area() {
        let l = [
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 2.0],
            [2.0, 2.0],
            [2.0, 4.0],
            [0.0, 4.0],
        ];
        let parts = convex_parts(&l).unwrap();
        let total: f64 = parts.iter().map(|p| signed_area(p)).sum();
        assert!((total - 12.0).abs() < 1e-9, "{total}");
        assert!(!contains(&l, [3.0, 3.0]));
    }

    #[test]
    fn clockwise_floor_is_rejected() {
        let cw = [[0.0, 0.0], [0.0, 3.0], [4.0, 3.0], [4.0, 0.0]];
        assert!(validate_floor(&cw).is_err());
    }
}
