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

    /// The pixels `rank` owns, in increasing order: the order in which it
    /// sends its composited pixels to rank 0.
    pub fn owned_pixels(&self, rank: usize) -> Vec<u32> {
        let n = u64::from(self.width) * u64::from(self.height);
        (0..n as u32).filter(|&p| self.owner(p) == rank).collect()
    }

    /// Pixels in the image.
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
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
        assert!(owned.iter().all(|o| o.windows(2).all(|w| w[0] < w[1])));
    }

    #[test]
    fn bad_layouts_are_errors() {
        assert!(TileLayout::new(0, 4, 16, 1).is_err());
        assert!(TileLayout::new(4, 4, 0, 1).is_err());
        assert!(TileLayout::new(4, 4, 16, 0).is_err());
    }
}
