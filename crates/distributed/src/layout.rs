//! Which process owns which pixels: the image in square tiles dealt out to
//! the ranks in turn (interleaved, so that every rank gets tiles from the
//! whole image and the work of compositing is spread evenly whatever part
//! of the image the mesh covers).

/// Tile edge in pixels, by default.
pub const DEFAULT_TILE: u32 = 16;

/// The image split into interleaved tiles over `ranks` processes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TileLayout {
    pub width: u32,
    pub height: u32,
    /// Tile edge in pixels.
    pub tile: u32,
    pub ranks: usize,
}

/// Why a [`TileLayout`] cannot be made.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LayoutError {
    #[error("image size {width}x{height}: both must be at least 1")]
    EmptyImage { width: u32, height: u32 },
    #[error("tile edge {0}: must be at least 1")]
    BadTile(u32),
    #[error("no ranks to share the image among")]
    NoRanks,
}

impl TileLayout {
    pub fn new(width: u32, height: u32, tile: u32, ranks: usize) -> Result<Self, LayoutError> {
        if width == 0 || height == 0 {
            return Err(LayoutError::EmptyImage { width, height });
        }
        if tile == 0 {
            return Err(LayoutError::BadTile(tile));
        }
        if ranks == 0 {
            return Err(LayoutError::NoRanks);
        }
        Ok(TileLayout {
            width,
            height,
            tile,
            ranks,
        })
    }

    fn tiles_x(&self) -> usize {
        self.width.div_ceil(self.tile) as usize
    }

    /// The rank owning pixel `y * width + x`: tiles in row order, dealt to
    /// ranks 0, 1, ..., P - 1, 0, 1, ...
    #[inline]
    pub fn owner(&self, pixel: u32) -> usize {
        let (x, y) = (pixel % self.width, pixel / self.width);
        let tile = (y / self.tile) as usize * self.tiles_x() + (x / self.tile) as usize;
        tile % self.ranks
    }

    fn tiles_y(&self) -> usize {
        self.height.div_ceil(self.tile) as usize
    }

    /// Tile `t`'s corner and size in pixels (tiles at the right and bottom
    /// edges may be smaller).
    fn tile_rect(&self, t: usize) -> (u32, u32, u32, u32) {
        let (tx, ty) = ((t % self.tiles_x()) as u32, (t / self.tiles_x()) as u32);
        let (x0, y0) = (tx * self.tile, ty * self.tile);
        (
            x0,
            y0,
            self.tile.min(self.width - x0),
            self.tile.min(self.height - y0),
        )
    }

    /// The tiles `rank` owns: `rank`, `rank + P`, ...
    fn owned_tiles(&self, rank: usize) -> impl Iterator<Item = usize> + use<> {
        (rank..self.tiles_x() * self.tiles_y()).step_by(self.ranks)
    }

    /// The pixels `rank` owns, tile after tile, row by row within a tile:
    /// the order of its composited pixels. O(pixels owned), so that no rank
    /// walks the whole image.
    pub fn owned_pixels(&self, rank: usize) -> Vec<u32> {
        let mut pixels = Vec::with_capacity(self.owned_count(rank));
        for t in self.owned_tiles(rank) {
            let (x0, y0, w, h) = self.tile_rect(t);
            for y in y0..y0 + h {
                pixels.extend((x0..x0 + w).map(|x| y * self.width + x));
            }
        }
        pixels
    }

    /// How many pixels `rank` owns.
    pub fn owned_count(&self, rank: usize) -> usize {
        self.owned_tiles(rank)
            .map(|t| {
                let (_, _, w, h) = self.tile_rect(t);
                w as usize * h as usize
            })
            .sum()
    }

    /// Where each pixel of `rank` goes in [`Self::owned_pixels`] order:
    /// `slot(pixel)` in O(1), or `None` for a pixel `rank` does not own.
    pub fn slots(&self, rank: usize) -> OwnedSlots {
        let mut starts = Vec::new();
        let mut at = 0;
        for t in self.owned_tiles(rank) {
            starts.push(at);
            let (_, _, w, h) = self.tile_rect(t);
            at += w as usize * h as usize;
        }
        OwnedSlots {
            layout: *self,
            rank,
            starts,
        }
    }

    /// Pixels in the image.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// The position of each owned pixel in a rank's composited pixels.
#[derive(Debug, Clone)]
pub struct OwnedSlots {
    layout: TileLayout,
    rank: usize,
    /// Per owned tile (in order), the slot of its first pixel.
    starts: Vec<usize>,
}

impl OwnedSlots {
    /// The slot of `pixel`, `None` when the rank does not own it.
    #[inline]
    pub fn slot(&self, pixel: u32) -> Option<usize> {
        let l = &self.layout;
        if pixel as usize >= l.pixels() || l.owner(pixel) != self.rank {
            return None;
        }
        let (x, y) = (pixel % l.width, pixel / l.width);
        let t = (y / l.tile) as usize * l.tiles_x() + (x / l.tile) as usize;
        let (x0, y0, w, _) = l.tile_rect(t);
        Some(self.starts[t / l.ranks] + ((y - y0) * w + (x - x0)) as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pixel_has_one_owner_and_tiles_interleave() {
        // 40x24 in 16-pixel tiles: 3 x 2 tiles, the last column and row
        // partial; 4 ranks get tiles 0..6 as 0,1,2,3,0,1.
        let layout = TileLayout::new(40, 24, 16, 4).unwrap();
        let owned: Vec<Vec<u32>> = (0..4).map(|r| layout.owned_pixels(r)).collect();
        let total: usize = owned.iter().map(Vec::len).sum();
        assert_eq!(total, 40 * 24);
        assert_eq!(layout.owner(0), 0);
        assert_eq!(layout.owner(16), 1);
        assert_eq!(layout.owner(39), 2);
        assert_eq!(layout.owner(16 * 40), 3);
        assert_eq!(layout.owner(16 * 40 + 16), 0);
        assert_eq!(layout.owner(23 * 40 + 39), 1);
        // Rank 0: tile 0 (16x16) and tile 4 (16x8).
        assert_eq!(owned[0].len(), 16 * 16 + 16 * 8);
        let mut all: Vec<u32> = owned.concat();
        all.sort_unstable();
        assert_eq!(all, (0..40 * 24).collect::<Vec<u32>>());
        // Each owned pixel's slot is its place in the owned order.
        for (rank, pixels) in owned.iter().enumerate() {
            assert_eq!(layout.owned_count(rank), pixels.len());
            let slots = layout.slots(rank);
            for (i, &p) in pixels.iter().enumerate() {
                assert_eq!(slots.slot(p), Some(i));
                assert_eq!(layout.owner(p), rank);
            }
            assert_eq!(slots.slot(40 * 24), None);
        }
        assert_eq!(layout.slots(0).slot(16), None);
    }

    #[test]
    fn bad_layouts_are_errors() {
        assert!(TileLayout::new(0, 4, 16, 1).is_err());
        assert!(TileLayout::new(4, 4, 0, 1).is_err());
        assert!(TileLayout::new(4, 4, 16, 0).is_err());
    }
}
