//! Shape of a row-major n-dimensional grid and its Fourier frequencies.

/// The shape of a row-major grid (last index fastest).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct GridShape {
    dims: Vec<usize>,
    strides: Vec<usize>,
}

impl GridShape {
    /// A grid with `dims[i]` nodes along axis `i`.
    pub fn new(dims: &[usize]) -> Self {
        let mut strides = vec![1; dims.len()];
        for axis in (0..dims.len().saturating_sub(1)).rev() {
            strides[axis] = strides[axis + 1] * dims[axis + 1];
        }
        Self {
            dims: dims.to_vec(),
            strides,
        }
    }

    /// Nodes per axis.
    pub fn dims(&self) -> &[usize] {
        &self.dims
    }

    /// Distance in the flat buffer between neighbours along each axis.
    pub fn strides(&self) -> &[usize] {
        &self.strides
    }

    /// Total number of nodes.
    pub fn len(&self) -> usize {
        self.dims.iter().product()
    }

    #[cfg(test)]
    /// Flat index of the node whose index on every axis is negated modulo the axis length: the
    /// position of the complex-conjugate partner of a Fourier coefficient.
    pub fn mirror(&self, flat: usize) -> usize {
        let mut rest = flat;
        let mut out = 0;
        for (&n, &stride) in self.dims.iter().zip(&self.strides) {
            let i = rest / stride;
            rest %= stride;
            out += ((n - i) % n) * stride;
        }
        out
    }

    #[cfg(test)]
    /// Squared frequency magnitude `Σ (k_i / N_i)²` of a flat index, in cycles per node, with
    /// `k_i` the signed wavenumber in `(−N_i/2, N_i/2]`.
    pub fn frequency_squared(&self, flat: usize) -> f64 {
        let mut rest = flat;
        let mut sum = 0.0;
        for (&n, &stride) in self.dims.iter().zip(&self.strides) {
            let i = rest / stride;
            rest %= stride;
            let k = signed_wavenumber(i, n) as f64 / n as f64;
            sum += k * k;
        }
        sum
    }
}

/// Signed wavenumber of FFT bin `i` of an `n`-point transform, in `(−n/2, n/2]`.
#[cfg(test)]
pub(crate) fn signed_wavenumber(i: usize, n: usize) -> i64 {
    if 2 * i <= n {
        i as i64
    } else {
        i as i64 - n as i64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mirror_is_an_involution_and_negates_wavenumbers() {
        let g = GridShape::new(&[3, 4, 5]);
        for flat in 0..g.len() {
            let m = g.mirror(flat);
            assert_eq!(g.mirror(m), flat);
            assert_eq!(g.frequency_squared(flat), g.frequency_squared(m));
        }
        assert_eq!(g.mirror(0), 0);
        // (0, 2, 0) is its own mirror in a 4-long axis: the Nyquist bin.
        assert_eq!(g.mirror(2 * 5), 2 * 5);
    }

    #[test]
    fn wavenumbers_cover_the_signed_range() {
        let ks: Vec<i64> = (0..6).map(|i| signed_wavenumber(i, 6)).collect();
        assert_eq!(ks, vec![0, 1, 2, 3, -2, -1]);
        let ks: Vec<i64> = (0..5).map(|i| signed_wavenumber(i, 5)).collect();
        assert_eq!(ks, vec![0, 1, 2, -2, -1]);
    }
}
