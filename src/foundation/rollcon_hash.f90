! SPDX-License-Identifier: MIT
!> FNV-1a, 64 bits (Fowler, Noll, Vo): a fast hash of bytes, to notice a file changed or cut on
!> disk (not against an adversary). The 64-bit state is kept as two 32-bit halves in int64, so
!> that no product overflows: h*prime mod 2**64 with prime = 2**40 + 435.
!>
!>     type(fnv1a64_type) :: hash
!>     call hash%add("a")
!>     print '(a)', hash%hex()     ! af63dc4c8601ec8c
module rollcon_hash
    use, intrinsic :: iso_fortran_env, only : int64
    implicit none
    private

    public :: fnv1a64_type

    !> 2**32 - 1 and 2**24 - 1
    integer(int64), parameter :: low32 = 4294967295_int64, low24 = 16777215_int64
    !> The prime's low part: 2**40 + 435
    integer(int64), parameter :: prime_low = 435_int64

    !> A hash being computed; starts at the offset basis cbf29ce484222325
    type :: fnv1a64_type
        integer(int64) :: high = int(z'cbf29ce4', int64), low = int(z'84222325', int64)
    contains
        procedure :: add
        procedure :: hex
    end type fnv1a64_type

contains

    !> Feed bytes.
    pure subroutine add(self, bytes)
        class(fnv1a64_type), intent(inout) :: self
        character(len=*), intent(in) :: bytes
        integer(int64) :: product_low
        integer :: j

        do j = 1, len(bytes)
            self%low = ieor(self%low, int(iachar(bytes(j:j)), int64))
            ! (high*2**32 + low)*(2**40 + 435) mod 2**64, in 32-bit halves
            product_low = self%low*prime_low
            self%high = iand(self%high*prime_low + ishft(product_low, -32) &
                & + iand(self%low, low24)*256_int64, low32)
            self%low = iand(product_low, low32)
        end do
    end subroutine add

    !> The hash as 16 lowercase hexadecimal digits.
    pure function hex(self) result(text)
        class(fnv1a64_type), intent(in) :: self
        character(len=16) :: text
        character(len=*), parameter :: digits = "0123456789abcdef"
        integer :: k
        integer(int64) :: part

        do k = 0, 7
            part = ishft(self%high, -4*(7 - k))
            text(k + 1:k + 1) = digits(iand(part, 15_int64) + 1:iand(part, 15_int64) + 1)
            part = ishft(self%low, -4*(7 - k))
            text(k + 9:k + 9) = digits(iand(part, 15_int64) + 1:iand(part, 15_int64) + 1)
        end do
    end function hex

end module rollcon_hash
