//! Parts of an image: the region a render covers (all of it, a `--region` or
//! a shard) and the tiles it is traced in, each small enough for the device
//! to hold its accumulation and read-back buffers.

/// The pixels [x0, x1) × [y0, y1) of an image, row 0 at the top.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Region {
    pub x0: u32,
    pub y0: u32,
    pub x1: u32,
    pub y1: u32,
}

impl Region {
    /// Every pixel of a `width` × `height` image.
    pub const fn whole(width: u32, height: u32) -> Self {
        Self { x0: 0, y0: 0, x1: width, y1: height }
    }

    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    pub fn pixels(&self) -> u64 {
        u64::from(self.width()) * u64::from(self.height())
    }

    pub fn is_empty(&self) -> bool {
        self.pixels() == 0
    }

    /// Whether every pixel of `inner` is one of this region's.
    pub fn contains(&self, inner: &Region) -> bool {
        self.x0 <= inner.x0 && self.y0 <= inner.y0 && inner.x1 <= self.x1 && inner.y1 <= self.y1
    }

    /// Whether the two regions share a pixel.
    pub fn overlaps(&self, other: &Region) -> bool {
        self.x0.max(other.x0) < self.x1.min(other.x1) && self.y0.max(other.y0) < self.y1.min(other.y1)
    }

    /// Shard `index` of `count` (from 0): horizontal strips of whole rows, as
    /// near equal in height as rows allow, top to bottom. Strips of rows keep
    /// each shard's file one contiguous run of the full image's rows.
    pub fn strip(&self, index: u32, count: u32) -> Region {
        let row = |i: u32| self.y0 + (u64::from(self.height()) * u64::from(i) / u64::from(count.max(1))) as u32;
        Region { y0: row(index), y1: row(index + 1), ..*self }
    }

    /// Tiles of at most `max_pixels` pixels that cover this region exactly
    /// once, in reading order. Tiles are whole rows of the region whenever a
    /// row fits, so a tile's accumulation is one run of the image's rows.
    pub fn tiles(&self, max_pixels: u64) -> Vec<Region> {
        let max_pixels = max_pixels.max(1);
        let tile_width = u64::from(self.width()).min(max_pixels) as u32;
        let tile_height = (max_pixels / u64::from(tile_width.max(1))).min(u64::from(self.height())) as u32;
        let mut tiles = Vec::new();
        if self.is_empty() {
            return tiles;
        }
        for y0 in (self.y0..self.y1).step_by(tile_height as usize) {
            for x0 in (self.x0..self.x1).step_by(tile_width as usize) {
                tiles.push(Region { x0, y0, x1: (x0 + tile_width).min(self.x1), y1: (y0 + tile_height).min(self.y1) });
            }
        }
        tiles
    }
}

impl std::fmt::Display for Region {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {} {} {}", self.x0, self.y0, self.x1, self.y1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// How many tiles cover each pixel of `region`.
    fn coverage(region: Region, tiles: &[Region]) -> Vec<u32> {
        let mut count = vec![0; region.pixels() as usize];
        for t in tiles {
            assert!(region.contains(t) && !t.is_empty(), "{t:?} outside {region:?} or empty");
            for y in t.y0..t.y1 {
                for x in t.x0..t.x1 {
                    count[((y - region.y0) * region.width() + x - region.x0) as usize] += 1;
                }
            }
        }
        count
    }

    #[test]
    fn tiles_cover_the_region_once_within_the_limit() {
        let region = Region { x0: 3, y0: 5, x1: 40, y1: 29 };
        for max_pixels in [1, 7, 36, 37, 100, 37 * 24, 1 << 40] {
            let tiles = region.tiles(max_pixels);
            assert!(tiles.iter().all(|t| t.pixels() <= max_pixels), "limit {max_pixels}");
            assert!(coverage(region, &tiles).iter().all(|&c| c == 1), "limit {max_pixels}");
        }
        assert_eq!(region.tiles(1 << 40), [region], "a region that fits is one tile");
        assert!(region.tiles(100).iter().all(|t| t.width() == 37), "rows are whole when one fits");
        assert!(Region::whole(0, 5).tiles(10).is_empty());
    }

    #[test]
    fn strips_split_the_rows_evenly_and_once() {
        let region = Region::whole(10, 7);
        let strips: Vec<Region> = (0..3).map(|i| region.strip(i, 3)).collect();
        assert_eq!(strips.iter().map(Region::height).collect::<Vec<_>>(), [2, 2, 3]);
        assert!(coverage(region, &strips).iter().all(|&c| c == 1));
        assert_eq!(region.strip(0, 1), region);
    }

    #[test]
    fn overlap_means_a_shared_pixel() {
        let a = Region { x0: 0, y0: 0, x1: 4, y1: 4 };
        assert!(a.overlaps(&Region { x0: 3, y0: 3, x1: 5, y1: 5 }));
        assert!(!a.overlaps(&Region { x0: 4, y0: 0, x1: 8, y1: 4 }), "touching edges share no pixel");
    }
}
