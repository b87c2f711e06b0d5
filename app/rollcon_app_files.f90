! SPDX-License-Identifier: MIT
!> The program's own file names: an output folder made when missing, a file's stem, and the
!> CSV a command's argument names.
module rollcon_app_files
    use rollcon, only : error_type, outputs_name_of
    use rollcon_program, only : make_folders
    implicit none
    private

    public :: make_folder, file_stem, folder_of, csv_argument

contains

    !> Create a folder and its parents, if missing: through mkdir(2), no shell and no PATH
    !> (the library's make_folders); every failure names the folder and the reason.
    subroutine make_folder(folder, error)
        !> Folder to create
        character(len=*), intent(in) :: folder
        type(error_type), allocatable, intent(out) :: error

        call make_folders(folder, error)
    end subroutine make_folder

    !> The file name of path without its folder and without extension (when it ends so):
    !> file_stem("out/coin.csv", ".csv") is "coin".
    pure function file_stem(path, extension) result(stem)
        character(len=*), intent(in) :: path, extension
        character(len=:), allocatable :: stem
        integer :: n

        stem = path(index(path, "/", back=.true.) + 1:)
        n = len(stem) - len(extension)
        if (n > 0 .and. len(extension) > 0) then
            if (stem(n + 1:) == extension) stem = stem(:n)
        end if
    end function file_stem

    !> The folder of a file ("." for a bare name).
    pure function folder_of(path) result(folder)
        character(len=*), intent(in) :: path
        character(len=:), allocatable :: folder
        integer :: slash

        slash = index(path, "/", back=.true.)
        folder = "."
        if (slash > 1) folder = path(:slash - 1)
        if (slash == 1) folder = "/"
    end function folder_of

    !> The CSV an argument names: itself when it ends in '.csv', else the CSV the run of that
    !> scene, dataset or command file writes into output_dir, output_dir/<name>.csv, <name> as
    !> the run names its outputs (outputs_name_of: `rollcon plot coin` plots the coin scene's
    !> run, `rollcon plot data/coin.adm` the dataset's, `rollcon plot MODEL.acf` the run of the
    !> command file, by the output name its second line gives or else its dataset's). A
    !> command file that cannot be read is refused as `rollcon run` refuses it.
    subroutine csv_argument(argument, output_dir, path, error)
        character(len=*), intent(in) :: argument, output_dir
        character(len=:), allocatable, intent(out) :: path
        type(error_type), allocatable, intent(out) :: error
        character(len=:), allocatable :: name

        if (len(argument) >= 4) then
            if (argument(len(argument) - 3:) == ".csv") then
                path = argument
                return
            end if
        end if
        call outputs_name_of(argument, name, error)
        if (allocated(error)) return
        path = output_dir // "/" // name // ".csv"
    end subroutine csv_argument

end module rollcon_app_files
