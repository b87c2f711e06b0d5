! SPDX-License-Identifier: MIT
!> rollcon's version: the `version` of fpm.toml (the test suite holds the two equal), as
!> `rollcon --version` prints it and every run's summary records it.
module rollcon_version
    implicit none
    private

    public :: rollcon_version_number, version_text

    !> The version, as fpm.toml writes it
    character(len=*), parameter :: rollcon_version_number = "0.2.0"

contains

    !> "rollcon 0.2.0".
    pure function version_text() result(text)
        character(len=:), allocatable :: text

        text = "rollcon " // rollcon_version_number
    end function version_text

end module rollcon_version
