//! A small, fast, deterministic hasher for the integer keys of the mesh and voxel stages
//! (vertex bit patterns, triangle and edge index tuples, grid cells).
//!
//! The standard `HashMap` uses SipHash with per-process random keys: robust against inputs
//! crafted to collide, but several times slower than needed for keys that are a few integers
//! and that come from a mesh, not from an adversary. This is the multiply-rotate hash of the
//! Firefox / rustc `FxHasher` (one rotate, xor and multiply per 64-bit word), written here
//! so that no crate is needed. Iteration order over a map built with it differs from
//! SipHash's, so it serves only where the result does not depend on that order (lookups,
//! counts, or an order fixed afterwards), as every use in this crate already had to be:
//! SipHash's order changes from run to run.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// The multiplier of rustc's `FxHasher` (64-bit).
const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

/// A word-at-a-time multiply-rotate hasher (see the module docs).
#[derive(Debug, Default, Clone, Copy)]
pub struct FastHasher {
    hash: u64,
}

impl FastHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FastHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for chunk in &mut chunks {
            let mut word = [0u8; 8];
            word.copy_from_slice(chunk);
            self.add(u64::from_le_bytes(word));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut word = [0u8; 8];
            word[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(word));
        }
    }

    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }

    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(u64::from(i));
    }

    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }

    #[inline]
    fn write_i64(&mut self, i: i64) {
        self.add(i as u64);
    }

    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    #[inline]
    fn finish(&self) -> u64 {
        self.hash
    }
}

/// A `HashMap` hashed with [`FastHasher`].
pub type FastMap<K, V> = HashMap<K, V, BuildHasherDefault<FastHasher>>;

/// An empty [`FastMap`] with room for `capacity` entries.
pub fn fast_map<K, V>(capacity: usize) -> FastMap<K, V> {
    FastMap::with_capacity_and_hasher(capacity, BuildHasherDefault::default())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::{BuildHasher, Hash};

    fn hash_of(key: impl Hash) -> u64 {
        BuildHasherDefault::<FastHasher>::default().hash_one(key)
    }

    #[test]
    fn equal_keys_hash_equal_and_near_keys_apart() {
        assert_eq!(hash_of([1u32, 2, 3]), hash_of([1u32, 2, 3]));
        assert_ne!(hash_of([1u32, 2, 3]), hash_of([1u32, 3, 2]));
        assert_ne!(hash_of([0i64, 0, 1]), hash_of([0i64, 1, 0]));
        // Byte strings longer than a word, and a tail, hash by every byte.
        assert_ne!(hash_of("abcdefghij"), hash_of("abcdefghik"));
    }

    #[test]
    fn a_map_of_grid_cells_finds_every_key() {
        let mut map: FastMap<[i64; 3], usize> = fast_map(0);
        let cells: Vec<[i64; 3]> = (-5..5)
            .flat_map(|x| (-5..5).flat_map(move |y| (-5..5).map(move |z| [x, y, z])))
            .collect();
        for (i, c) in cells.iter().enumerate() {
            map.insert(*c, i);
        }
        assert_eq!(map.len(), cells.len());
        assert!(cells.iter().enumerate().all(|(i, c)| map[c] == i));
    }
}
