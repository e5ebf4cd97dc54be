//! BVH invariants: bounds that contain their children, SAH splits that beat a
//! median split, bounded depth on adversarial input, non-finite bounds, and
//! build throughput.

use super::*;
use crate::test_rng::Rng;

/// Boxes in a 100³ volume with per-axis sizes spread over three decades.
fn random_boxes(seed: u64, n: usize) -> Vec<(Vec3, Vec3)> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| {
            let center = rng.vec3(0.0, 100.0);
            let half = Vec3::new(
                10f32.powf(rng.range(-2.0, 1.0)),
                10f32.powf(rng.range(-2.0, 1.0)),
                10f32.powf(rng.range(-2.0, 1.0)),
            );
            (center - half, center + half)
        })
        .collect()
}

fn contains(outer: &Node, min: Vec3, max: Vec3) -> bool {
    Vec3::from(outer.min).cmple(min).all() && Vec3::from(outer.max).cmpge(max).all()
}

/// Checks every structural promise of the layout and of the builder.
fn check(bvh: &Bvh, bounds: &[(Vec3, Vec3)]) {
    let n = bounds.len();
    let mut sorted = bvh.order.clone();
    sorted.sort_unstable();
    assert!(sorted.iter().copied().eq(0..n as u32), "order is not a permutation");

    let mut visited = vec![false; bvh.nodes.len()];
    let mut ranges = Vec::new();
    let mut stack = vec![0usize];
    while let Some(i) = stack.pop() {
        assert!(!std::mem::replace(&mut visited[i], true), "node {i} reached twice");
        let node = &bvh.nodes[i];
        if node.is_leaf() {
            assert!(node.count as usize <= MAX_LEAF, "leaf of {}", node.count);
            let range = node.left_or_first as usize..(node.left_or_first + node.count) as usize;
            for &p in &bvh.order[range.clone()] {
                let (min, max) = bounds[p as usize];
                assert!(contains(node, min, max), "leaf {i} misses primitive {p}");
            }
            ranges.push(range);
        } else {
            let left = node.left_or_first as usize;
            for child in [left, left + 1] {
                let c = &bvh.nodes[child];
                assert!(contains(node, c.min.into(), c.max.into()), "child {child} outside {i}");
                stack.push(child);
            }
        }
    }
    assert!(visited.iter().all(|&v| v), "unreachable nodes");
    ranges.sort_by_key(|r| r.start);
    let mut next = 0;
    for r in ranges {
        assert_eq!(r.start, next, "leaf ranges overlap or leave a gap");
        next = r.end;
    }
    assert_eq!(next, n, "leaf ranges do not cover the primitives");
    assert!(bvh.depth() <= MAX_DEPTH, "depth {}", bvh.depth());
}

/// Reference builder: object median on the widest centroid axis, leaves of at
/// most `MAX_LEAF`.
fn median_split(bounds: &[(Vec3, Vec3)]) -> Bvh {
    fn recurse(bounds: &[(Vec3, Vec3)], order: &mut [u32], first: u32, nodes: &mut Vec<Node>, slot: usize) {
        let mut b = Aabb::EMPTY;
        let mut c = Aabb::EMPTY;
        for &i in order.iter() {
            let (min, max) = bounds[i as usize];
            b.grow(&Aabb { min: min.into(), max: max.into() });
            c.grow_point(((min + max) * 0.5).into());
        }
        if order.len() <= MAX_LEAF {
            nodes[slot] = Node::leaf(b, first, order.len());
            return;
        }
        let axis = (c.max - c.min).max_position();
        let key = |i: &u32| {
            let (min, max) = bounds[*i as usize];
            (min + max)[axis]
        };
        order.sort_unstable_by(|a, b| key(a).total_cmp(&key(b)));
        let child = nodes.len();
        nodes[slot] = Node::interior(b, child as u32);
        nodes.extend([Node::zeroed(); 2]);
        let mid = order.len() / 2;
        let (l, r) = order.split_at_mut(mid);
        recurse(bounds, l, first, nodes, child);
        recurse(bounds, r, first + mid as u32, nodes, child + 1);
    }
    let mut order: Vec<u32> = (0..bounds.len() as u32).collect();
    let mut nodes = vec![Node::zeroed()];
    recurse(bounds, &mut order, 0, &mut nodes, 0);
    Bvh { nodes, order }
}

#[test]
fn empty_input_is_the_empty_single_leaf() {
    let bvh = Bvh::build(&[]);
    assert_eq!(bvh, Bvh::single_leaf(&[]));
    assert_eq!(bvh.nodes[0].count, 1);
    assert!(bvh.nodes[0].min[0] > bvh.nodes[0].max[0]);
    assert_eq!(bvh.depth(), 0);
    assert_eq!(bvh.sah_cost(), 0.0);
}

#[test]
fn single_primitive_is_one_leaf() {
    let bounds = [(Vec3::new(1.0, 2.0, 3.0), Vec3::new(4.0, 5.0, 6.0))];
    let bvh = Bvh::build(&bounds);
    assert_eq!(bvh, Bvh::single_leaf(&bounds));
    assert_eq!(bvh.sah_cost(), C_ISECT);
}

#[test]
fn random_scenes_are_valid_and_beat_median_split() {
    for (seed, n) in [(1, 1000), (2, 2500), (3, 5000), (4, 10_000), (5, 37), (6, 5)] {
        let bounds = random_boxes(seed, n);
        let bvh = Bvh::build(&bounds);
        check(&bvh, &bounds);
        let median = median_split(&bounds);
        check(&median, &bounds);
        let (sah, reference) = (bvh.sah_cost(), median.sah_cost());
        assert!(sah <= reference, "seed {seed}: SAH {sah} vs median {reference}");
    }
}

#[test]
fn depth_is_bounded_on_adversarial_input() {
    let unit = |c: Vec3| (c - 0.5, c + 0.5);
    let cases: Vec<(&str, Vec<(Vec3, Vec3)>)> = vec![
        ("points at x = 2^i", (0..127).map(|i| (Vec3::X * 2f32.powi(i), Vec3::X * 2f32.powi(i))).collect()),
        ("unit boxes at x = 1.1^i", (0..900).map(|i| unit(Vec3::X * 1.1f32.powi(i))).collect()),
        (
            "nested boxes",
            (0..2000).map(|i| (Vec3::splat(-1.01f32.powi(i)), Vec3::splat(1.01f32.powi(i)))).collect(),
        ),
        ("identical boxes", vec![(Vec3::ZERO, Vec3::ONE); 100_000]),
        ("points on a line", (0..50_000).map(|i| (Vec3::splat(i as f32), Vec3::splat(i as f32))).collect()),
        ("spheres on a line", (0..50_000).map(|i| unit(Vec3::X * i as f32 * 0.01)).collect()),
        (
            "flat boxes in a plane",
            random_boxes(7, 20_000).into_iter().map(|(min, max)| (min.with_z(0.0), max.with_z(0.0))).collect(),
        ),
    ];
    for (name, bounds) in cases {
        let bvh = Bvh::build(&bounds);
        assert!(bvh.depth() <= MAX_DEPTH, "{name}: depth {}", bvh.depth());
        check(&bvh, &bounds);
    }
}

#[test]
fn non_finite_bounds_still_build() {
    // Garbage in must not panic, loop or lose primitives.
    let mut bounds = random_boxes(8, 200);
    bounds[3] = (Vec3::NAN, Vec3::NAN);
    bounds[50] = (Vec3::NEG_INFINITY, Vec3::INFINITY);
    bounds[100].1.x = f32::INFINITY;
    bounds[150].0 = Vec3::new(f32::NAN, 0.0, f32::NEG_INFINITY);
    for bounds in [bounds, vec![(Vec3::NAN, Vec3::NAN); 100], vec![(Vec3::NEG_INFINITY, Vec3::INFINITY); 100]] {
        let bvh = Bvh::build(&bounds);
        let mut order = bvh.order.clone();
        order.sort_unstable();
        assert!(order.iter().copied().eq(0..bounds.len() as u32));
        assert!(bvh.depth() <= MAX_DEPTH);
    }
}

/// Process CPU time (user + system), which unlike wall time does not count
/// waiting for other processes on a busy machine. Linux only.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap();
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap().split_whitespace().collect();
    let ticks: f64 = fields[11].parse::<f64>().unwrap() + fields[12].parse::<f64>().unwrap();
    ticks / 100.0
}

/// `cargo test --release -p glint-scene bvh_throughput -- --ignored --nocapture`
#[test]
#[ignore = "benchmark"]
fn bvh_throughput() {
    let n = 1_000_000;
    let runs = 5;
    let bounds = random_boxes(9, n);
    Bvh::build(&bounds[..100_000]); // warm up the thread pool
    let mut times = Vec::new();
    let cpu = cpu_seconds();
    for _ in 0..runs {
        let start = std::time::Instant::now();
        std::hint::black_box(Bvh::build(&bounds));
        times.push(start.elapsed().as_secs_f64());
    }
    let cpu = (cpu_seconds() - cpu) / runs as f64;
    let bvh = Bvh::build(&bounds);
    let best = times.iter().copied().fold(f64::INFINITY, f64::min);
    println!(
        "{n} boxes, {} threads: best {:.0} ms wall ({:.2} M prims/s), runs {:?} ms; {:.0} ms CPU per build; \
         {} nodes, depth {}, SAH {:.1} (median split {:.1})",
        rayon::current_num_threads(),
        best * 1e3,
        n as f64 / best / 1e6,
        times.iter().map(|t| (t * 1e3).round()).collect::<Vec<_>>(),
        cpu * 1e3,
        bvh.nodes.len(),
        bvh.depth(),
        bvh.sah_cost(),
        median_split(&bounds).sah_cost(),
    );
}

/// A tree a little over its node budget is rebuilt within it, with dearer
/// nodes and every invariant kept; a tree within its budget, or far over it,
/// is the SAH tree as `build` makes it.
#[test]
fn a_tree_near_its_node_budget_is_built_within_it() {
    let bounds = random_boxes(7, 2000);
    let sah = Bvh::build(&bounds);
    let budget = sah.nodes.len() * 9 / 10;
    let within = Bvh::build_within(&bounds, budget);
    check(&within, &bounds);
    assert!(within.nodes.len() <= budget, "{} nodes for a budget of {budget}", within.nodes.len());
    assert!(within.sah_cost() > sah.sah_cost(), "the SAH tree is the cheapest by its own measure");
    assert_eq!(Bvh::build_within(&bounds, sah.nodes.len()).nodes, sah.nodes);
    assert_eq!(Bvh::build_within(&bounds, sah.nodes.len() / 2).nodes, sah.nodes);
}
